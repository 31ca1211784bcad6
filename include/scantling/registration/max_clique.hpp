#pragma once
/// @file
/// Maximum clique of an undirected graph: the inlier selector of TEASER++ (Yang, Shi & Carlone,
/// T-RO 2020), where vertices are correspondences and edges join mutually consistent pairs.
///
/// Exact solver (after PMC, Rossi et al. 2015, and BBMC/MCS, San Segundo 2011 / Tomita 2010):
/// 1. core numbers by the O(V + E) peeling of Batagelj & Zaversnik; a vertex of core number k
///    lies in no clique larger than k + 1;
/// 2. a greedy clique in degeneracy order gives a lower bound L; vertices with core < L are
///    dropped;
/// 3. for each remaining vertex v, in degeneracy order, branch and bound over its later
///    neighbours (a bitset subgraph of at most degeneracy vertices), with greedy colouring
///    bounds: a colour class holds no two adjacent vertices, so c colours bound the clique by c.
/// The branch and bound counts its search nodes; past `max_search_nodes` it stops and returns
/// the best clique found so far (method kTruncated). Graphs whose pruned vertex count exceeds
/// `max_vertices_exact` get the greedy clique only (method kGreedy).
///
/// Cost: O(V + E) for the cores and the greedy bound; the exact search is exponential in the
/// worst case but fast on the sparse-plus-dense-core graphs of registration.
/// Thread-safety: pure function. @note Deterministic (search-node budget, not wall time).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

namespace scantling::registration {

/// Simple undirected graph as adjacency lists: `neighbors[v]` ascending, no self-loops, and
/// u ∈ neighbors[v] exactly when v ∈ neighbors[u].
struct UndirectedGraph {
    std::vector<std::vector<std::uint32_t>> neighbors;

    std::size_t num_vertices() const { return neighbors.size(); }
    std::size_t num_edges() const;
};

/// Graph on `num_vertices` vertices from an edge list (either orientation; duplicates merged).
/// Throws InputError on a self-loop or a vertex index >= num_vertices.
UndirectedGraph graph_from_edges(std::size_t num_vertices,
                                 std::span<const std::pair<std::uint32_t, std::uint32_t>> edges);

/// Core number of every vertex (the largest k such that the vertex is in the k-core).
std::vector<std::uint32_t> core_numbers(const UndirectedGraph& graph);

/// How the returned clique was found.
enum class MaxCliqueMethod {
    kExact,      ///< branch and bound finished: the clique is maximum
    kTruncated,  ///< branch and bound hit max_search_nodes: best found, maybe not maximum
    kGreedy,     ///< exact search skipped (too many vertices or disabled): greedy clique
};

/// "exact", "truncated", "greedy".
std::string_view to_string(MaxCliqueMethod method);

struct MaxCliqueConfig {
    /// Run the exact branch and bound (false: greedy clique only, TEASER++'s heuristic mode).
    bool solve_exactly = true;
    /// Most vertices left after core pruning for which the exact search is attempted, >= 1.
    /// Beyond, the greedy clique is returned. 20000 covers every realistic correspondence set
    /// (the exact search works on subgraphs of at most degeneracy + 1 vertices anyway).
    std::size_t max_vertices_exact = 20000;
    /// Search-node budget of the branch and bound, >= 1. One node costs about a bitset AND of
    /// degeneracy/64 words plus a colouring. 10⁵: the 3DMatch pair needs 1.2·10³ nodes for 848
    /// matches at 0.05 m voxels (2.7·10⁴ for 3622 matches of the raw 16k-point fragments), but
    /// pairs of 360° LiDAR scans of the distillation column (~5000 matches, ~1.5·10⁶ consistent
    /// pairs) exhausted 10⁷ nodes in 16–23 s; 10⁵ took 0.2–0.4 s there and returned cliques of
    /// 92–97 % the size with the same pose error (0.4–0.6°, 1–2 cm).
    std::size_t max_search_nodes = 100'000;

    /// Throws ConfigError("<prefix>.max_search_nodes = 0, expected >= 1").
    void validate(std::string_view prefix = "max_clique") const;
};

struct MaxCliqueResult {
    std::vector<std::uint32_t> vertices;  ///< the clique, ascending
    MaxCliqueMethod method = MaxCliqueMethod::kExact;
    std::size_t search_nodes = 0;  ///< branch-and-bound nodes visited
    std::uint32_t degeneracy = 0;  ///< largest core number (clique size <= degeneracy + 1)
};

/// Maximum (or, see method, large) clique of `graph`. An empty graph gives an empty clique; a
/// graph without edges gives a single vertex (the lowest index). Among maximum cliques the one
/// found first in degeneracy order is returned, the same one on every run.
/// Throws ConfigError on a bad config. The graph is assumed well formed (graph_from_edges).
MaxCliqueResult find_max_clique(const UndirectedGraph& graph, const MaxCliqueConfig& config = {});

}  // namespace scantling::registration
