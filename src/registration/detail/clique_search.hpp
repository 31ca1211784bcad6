#pragma once
/// @file
/// Branch and bound for the maximum clique within one vertex's neighbourhood (private to
/// max_clique.cpp): bitset adjacency and greedy colouring bounds (BBMC, San Segundo 2011).

#include <cstddef>
#include <cstdint>
#include <vector>

#include <scantling/registration/max_clique.hpp>

namespace scantling::registration::detail {

/// Shared state of the exact search over all root vertices.
struct CliqueSearchState {
    std::vector<std::uint32_t> best;  ///< largest clique so far (global vertex ids)
    std::size_t nodes = 0;            ///< search nodes visited so far
    std::size_t max_nodes = 0;        ///< budget
    bool truncated = false;           ///< the budget ran out
};

/// The whole adjacency as an n × n bit matrix, for O(1) edge tests while building the
/// candidate subgraphs (n²/8 bytes: used up to kMaxDenseVertices vertices).
class DenseAdjacency {
  public:
    static constexpr std::size_t kMaxDenseVertices = 16384;  // 32 MiB

    explicit DenseAdjacency(const UndirectedGraph& graph);
    bool connected(std::uint32_t a, std::uint32_t b) const {
        return (bits_[a * words_ + b / 64] >> (b % 64)) & 1u;
    }

  private:
    std::size_t words_ = 0;
    std::vector<std::uint64_t> bits_;
};

/// Searches for a clique larger than `state.best` that contains `root` and otherwise only
/// vertices of `candidates` (ascending, all adjacent to `root`). Updates `state`. `dense` (may
/// be null) speeds up building the candidate subgraph.
void search_rooted_clique(const UndirectedGraph& graph, const DenseAdjacency* dense,
                          std::uint32_t root, const std::vector<std::uint32_t>& candidates,
                          CliqueSearchState& state);

}  // namespace scantling::registration::detail
