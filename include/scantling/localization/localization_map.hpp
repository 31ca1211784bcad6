#pragma once
/// @file
/// The known map a Localizer registers against (SPEC §7): the CAD cloud downsampled once, with
/// normals, a k-d tree, FPFH descriptors for global re-localisation, and the structural map
/// (compartments) that restricts the global search.
///
/// Normals: a CAD map sampled on both faces of thin plates has opposite normals a centimetre
/// apart; a plain voxel average would cancel them. The map is therefore downsampled per
/// dominant normal direction (six classes, ±x, ±y, ±z), keeping both faces. A map without
/// normals gets them estimated, oriented towards the map's centroid (inside a tank, the free
/// side of every wall faces it).
///
/// Descriptor cache: FPFH over a whole tank takes seconds; they are computed once per map and
/// config and kept in a binary file (`<map>.fpfh`, or a path given). The file holds a key over
/// the downsampled cloud and the settings, so a changed map or config recomputes it; a
/// corrupt, truncated or stale file is recomputed and replaced (reported), never trusted.
///
/// Thread-safety: immutable after build; every const method may be called concurrently.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <scantling/core/kdtree.hpp>
#include <scantling/core/parallel.hpp>
#include <scantling/core/point_cloud.hpp>
#include <scantling/io/structural_map.hpp>
#include <scantling/localization/correlative_search.hpp>
#include <scantling/registration/fpfh.hpp>

namespace scantling::localization {

struct LocalizationMapConfig {
    /// Voxel edge of the map (and of the frames registered against it), metres, > 0. SPEC §7:
    /// 0.04–0.05 m; the ICP covariance model was validated at 0.05 m (docs/results.md).
    double voxel_size_m = 0.05;
    /// Neighbours for normals when the map has none, >= 3 (30: ~2 voxels each way).
    int normal_neighbors = 30;
    registration::FpfhConfig fpfh;  ///< radius 0.25 m = 5 voxels (Open3D's, TEASER++'s examples)
    /// A compartment's region is its box grown by this much, metres, >= 0, so the walls that
    /// bound it (sampled on their faces, on the box) and what is seen through a manhole belong
    /// to it.
    double compartment_margin_m = 0.3;
    LikelihoodFieldConfig likelihood;  ///< for the correlative re-localisation
    ParallelConfig parallel;

    void validate(std::string_view prefix = "map") const;
};

/// Part of the map with its own tree and descriptors: one compartment, or the whole map.
struct MapRegion {
    int compartment = -1;  ///< -1: the whole map
    PointCloud cloud;      ///< downsampled, with normals
    std::unique_ptr<KdTree> tree;
    registration::FeatureMatrix descriptors;  ///< one column per point
};

/// How the descriptors were obtained.
enum class DescriptorSource { kComputed, kCache, kRecomputedStale };

class LocalizationMap {
  public:
    /// Prepares `map` (any frame called "world"; finite points, >= 10 after downsampling).
    /// `cache_path` empty: no cache. Throws InputError for an unusable cloud (naming it),
    /// ConfigError for a bad config; cache write failures are reported, not thrown.
    static LocalizationMap build(const PointCloud& map, std::optional<io::StructuralMap> structure,
                                 const LocalizationMapConfig& config,
                                 const std::string& cache_path = "");

    const MapRegion& whole() const { return *regions_.front(); }
    /// The region of compartment `id` (the whole map when unknown or without metadata).
    const MapRegion& region(int compartment_id) const;
    const std::vector<std::unique_ptr<MapRegion>>& regions() const { return regions_; }
    const io::StructuralMap* structure() const { return structure_ ? &*structure_ : nullptr; }
    const LikelihoodField& likelihood() const { return likelihood_; }
    const LocalizationMapConfig& config() const { return config_; }
    DescriptorSource descriptor_source() const { return descriptor_source_; }
    /// Non-empty when the cache could not be read or written (why).
    const std::string& cache_message() const { return cache_message_; }

  private:
    LocalizationMapConfig config_;
    std::optional<io::StructuralMap> structure_;
    std::vector<std::unique_ptr<MapRegion>> regions_;  ///< [0] = whole map, then compartments
    LikelihoodField likelihood_;
    DescriptorSource descriptor_source_ = DescriptorSource::kComputed;
    std::string cache_message_;
};

/// Downsampling that keeps the two faces of a thin plate apart (see the file comment).
PointCloud downsample_by_normal_class(const PointCloud& cloud, double voxel_size_m,
                                      const ParallelConfig& parallel = {});

/// Key of a descriptor cache: FNV-1a over the cloud's points and normals and the settings.
std::uint64_t descriptor_cache_key(const PointCloud& cloud, const LocalizationMapConfig& config);
/// Reads descriptors for `key` and `num_points` from `path`; nullopt with `why` set when the
/// file is missing, malformed or for another key.
std::optional<registration::FeatureMatrix> read_descriptor_cache(const std::string& path,
                                                                 std::uint64_t key,
                                                                 std::size_t num_points,
                                                                 std::string& why);
/// Writes atomically (FileError on failure).
void write_descriptor_cache(const std::string& path, std::uint64_t key,
                            const registration::FeatureMatrix& descriptors);

}  // namespace scantling::localization
