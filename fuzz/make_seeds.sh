#!/usr/bin/env bash
# Builds the seed corpus of every fuzz target into OUT/<target>/ (docs/fuzzing.md):
#   - the small hand-written seeds in fuzz/seeds/ and the repository's YAML (config/, scenarios/);
#   - cut-down copies of the real files in the shared data folder (../shared/data, or
#     $SCANTLING_SHARED_DATA), made at run time: nothing from it is stored in the repository;
#   - a packed real recording, simulated with fuzz/seeds/recording_scenario.yaml when a built
#     `scantling` CLI is given.
# Usage: fuzz/make_seeds.sh OUT [SCANTLING_CLI]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$1"
cli="${2:-}"
data="${SCANTLING_SHARED_DATA:-$root/../shared/data}"
targets=(pcd ply kitti_bin kitti_poses tum config scenario recording structural_map)

# Points kept from a real cloud: enough for every field to vary, small enough to mutate quickly.
seed_points=48

# Byte length of the first $2 lines of file $1.
head_bytes() { head -n "$2" "$1" | wc -c; }

# $3 bytes of file $1 from byte offset $2 (dd: no SIGPIPE from a cut pipe under pipefail).
bytes_at() { dd if="$1" iflag=skip_bytes,count_bytes skip="$2" count="$3" status=none; }

# Binary PCD $1 cut to its first $seed_points points, header counts rewritten to match.
cut_pcd() {
  local src="$1" dst="$2" lines point_bytes
  lines=$(grep -a -n -m1 '^DATA' "$src" | cut -d: -f1)
  point_bytes=$(head -n "$lines" "$src" | awk '
    $1 == "SIZE" { for (i = 2; i <= NF; i++) size[i] = $i }
    $1 == "COUNT" { for (i = 2; i <= NF; i++) count[i] = $i }
    END { for (i in size) total += size[i] * ((i in count) ? count[i] : 1); print total }')
  {
    head -n "$lines" "$src" | sed -e "s/^WIDTH .*/WIDTH $seed_points/" \
      -e "s/^HEIGHT .*/HEIGHT 1/" -e "s/^POINTS .*/POINTS $seed_points/"
    bytes_at "$src" "$(head_bytes "$src" "$lines")" "$((seed_points * point_bytes))"
  } > "$dst"
}

# Binary PLY $1 whose only element is `vertex` (scalar properties), cut to $seed_points vertices,
# on stdout (nothing for other files).
cut_ply() {
  local src="$1" lines vertex_bytes
  lines=$(grep -a -n -m1 '^end_header' "$src" | cut -d: -f1)
  vertex_bytes=$(head -n "$lines" "$src" | awk '
    BEGIN { split("char 1 uchar 1 int8 1 uint8 1 short 2 ushort 2 int16 2 uint16 2 int 4 uint 4 " \
                  "int32 4 uint32 4 float 4 float32 4 double 8 float64 8", kv, " ")
            for (i = 1; i < 32; i += 2) bytes[kv[i]] = kv[i + 1] }
    $1 == "element" { in_vertex = ($2 == "vertex"); if (!in_vertex) other = 1 }
    $1 == "property" && in_vertex { if ($2 == "list") other = 1; else total += bytes[$2] }
    END { print other ? 0 : total }')
  [[ "$vertex_bytes" -gt 0 ]] || return 0
  {
    head -n "$lines" "$src" | sed -e "s/^element vertex .*/element vertex $seed_points/"
    bytes_at "$src" "$(head_bytes "$src" "$lines")" "$((seed_points * vertex_bytes))"
  }
}

# KITTI 3x4 poses $1 (first $3 lines) as a TUM trajectory 0.1 s apart (quaternion from R).
kitti_to_tum() {
  head -n "$3" "$1" | awk '{
    r11 = $1; r12 = $2; r13 = $3; r21 = $5; r22 = $6; r23 = $7; r31 = $9; r32 = $10; r33 = $11
    t = r11 + r22 + r33
    if (t > 0) { s = sqrt(t + 1) * 2; w = s / 4; x = (r32 - r23) / s; y = (r13 - r31) / s; z = (r21 - r12) / s }
    else if (r11 > r22 && r11 > r33) { s = sqrt(1 + r11 - r22 - r33) * 2; w = (r32 - r23) / s; x = s / 4; y = (r12 + r21) / s; z = (r13 + r31) / s }
    else if (r22 > r33) { s = sqrt(1 + r22 - r11 - r33) * 2; w = (r13 - r31) / s; x = (r12 + r21) / s; y = s / 4; z = (r23 + r32) / s }
    else { s = sqrt(1 + r33 - r11 - r22) * 2; w = (r21 - r12) / s; x = (r13 + r31) / s; y = (r23 + r32) / s; z = s / 4 }
    printf "%.6f %s %s %s %.9f %.9f %.9f %.9f\n", (NR - 1) * 0.1, $4, $8, $12, x, y, z, w }' > "$2"
}

# A binary_compressed PCD (x y z, 2 points) in two LZF forms: one literal run, and a literal
# run followed by a back reference (printf: the format is binary).
write_compressed_pcds() {
  local header='VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA binary_compressed\n'
  printf "${header}"'\x19\x00\x00\x00\x18\x00\x00\x00\x17AAAABBBBCCCCDDDDEEEEFFFF' > "$1/compressed_literal.pcd"
  printf "${header}"'\x08\x00\x00\x00\x18\x00\x00\x00\x03AAAA\xe0\x0b\x03' > "$1/compressed_backref.pcd"
}

# Packs recording folder $1 into archive $2 (recording_archive.hpp): the first two frames of
# each stream, text files cut to a few lines, the files open_recording does not read left out.
pack_recording() {
  local dir="$1" file rel
  (cd "$dir" && find . -type f | sort) | while read -r file; do
    rel="${file#./}"
    case "$rel" in world/* | summary.json | timing.json | *.png) continue ;; esac
    if [[ "$rel" =~ /[0-9]{6}\. && ! "$rel" =~ /00000[01]\. ]]; then continue; fi
    printf '@@ %s\n' "$rel"
    case "$rel" in
      */times.txt | */poses_gt.txt) head -n 2 "$dir/$rel" ;;
      *.bin) head -c 512 "$dir/$rel" ;;
      *.ply) cut_ply "$dir/$rel" ;;
      *) head -n 6 "$dir/$rel" ;;
    esac
    printf '\n'  # the separator before the next entry (not part of the content)
  done > "$2"
}

rm -rf "$out"
for t in "${targets[@]}"; do mkdir -p "$out/$t"; done
for t in pcd ply kitti_bin kitti_poses tum recording structural_map; do cp "$root"/fuzz/seeds/"$t"/* "$out/$t/"; done
write_compressed_pcds "$out/pcd"
cp "$root"/config/odometry/*.yaml "$root"/config/odometry/examples/*.yaml "$root"/config/localization/*.yaml \
  "$out/config/"
cp "$root"/scenarios/*.yaml "$root"/fuzz/seeds/recording_scenario.yaml "$out/scenario/"
for t in config scenario; do cp "$root"/fuzz/seeds/yaml/* "$out/$t/"; done

if [[ -d "$data" ]]; then
  for i in 000000 000007; do
    cut_pcd "$data/lidar-scans/$i.pcd" "$out/pcd/real_$i.pcd"
    head -c 8192 "$data/lidar-scans/$i.pcd" > "$out/pcd/real_${i}_first_8k.pcd"
    # The float32 records of a real sweep are plausible KITTI velodyne data too.
    tail -c 2048 "$data/lidar-scans/$i.pcd" > "$out/kitti_bin/real_$i.bin"
  done
  for f in lidar-pair/source rgbd-pair/src; do
    cut_ply "$data/$f.ply" > "$out/ply/real_${f//\//_}.ply"
    head -c 8192 "$data/$f.ply" > "$out/ply/real_${f//\//_}_first_8k.ply"
  done
  for seq in 00 05; do
    head -n 40 "$data/kitti-poses/groundtruth/$seq.txt" > "$out/kitti_poses/real_gt_$seq.txt"
    head -n 40 "$data/kitti-poses/simple-estimates/$seq.txt" > "$out/kitti_poses/real_est_$seq.txt"
    kitti_to_tum "$data/kitti-poses/groundtruth/$seq.txt" "$out/tum/real_gt_$seq.tum" 40
  done
  cp "$data"/lidar-pair/T_target_source.txt "$data"/rgbd-pair/T_ref_src.txt "$out/kitti_poses/" 2>/dev/null || true
else
  echo "make_seeds: $data not found: seeds from the repository only (no real clouds or poses)"
fi

if [[ -n "$cli" && -x "$cli" ]]; then
  recording="$out/../seed-recording"
  if "$cli" sim "$root/fuzz/seeds/recording_scenario.yaml" --out "$recording" --force --no-progress \
       > "$out/../seed-recording.log" 2>&1; then
    pack_recording "$recording" "$out/recording/simulated.rec"
  else
    echo "make_seeds: simulating the seed recording failed (see $out/../seed-recording.log)"
  fi
else
  echo "make_seeds: no scantling CLI given: the recording seeds are the hand-written ones only"
fi
for t in "${targets[@]}"; do printf 'make_seeds: %-12s %3d seeds\n' "$t" "$(ls "$out/$t" | wc -l)"; done
