#include "clique_search.hpp"

#include <algorithm>
#include <bit>
#include <numeric>
#include <utility>

namespace scantling::registration::detail {
namespace {

using Word = std::uint64_t;

/// Adjacency of the candidate subgraph as one bitset row per local vertex. Local vertices are
/// ordered by decreasing degree in the whole graph (BBMC orders by degree so that the greedy
/// colouring is tight; the subgraph's own degrees would cost a second pass).
class LocalGraph {
  public:
    LocalGraph(const UndirectedGraph& graph, const DenseAdjacency* dense,
               const std::vector<std::uint32_t>& candidates);

    std::size_t size() const { return ids_.size(); }
    std::size_t words() const { return words_; }
    const Word* row(std::size_t v) const { return &bits_[v * words_]; }
    std::uint32_t global_id(std::size_t v) const { return ids_[v]; }

  private:
    void set(std::size_t a, std::size_t b) { bits_[a * words_ + b / 64] |= Word{1} << (b % 64); }
    void fill_dense(const DenseAdjacency& dense);
    void fill_sparse(const UndirectedGraph& graph);

    std::vector<std::uint32_t> ids_;
    std::size_t words_ = 0;
    std::vector<Word> bits_;
};

LocalGraph::LocalGraph(const UndirectedGraph& graph, const DenseAdjacency* dense,
                       const std::vector<std::uint32_t>& candidates)
    : ids_(candidates), words_((candidates.size() + 63) / 64), bits_(ids_.size() * words_, 0) {
    std::stable_sort(ids_.begin(), ids_.end(), [&](std::uint32_t x, std::uint32_t y) {
        return graph.neighbors[x].size() > graph.neighbors[y].size();
    });
    if (dense != nullptr) {
        fill_dense(*dense);
    } else {
        fill_sparse(graph);
    }
}

void LocalGraph::fill_dense(const DenseAdjacency& dense) {
    for (std::size_t a = 0; a < ids_.size(); ++a) {
        for (std::size_t b = 0; b < ids_.size(); ++b) {
            if (dense.connected(ids_[a], ids_[b])) set(a, b);
        }
    }
}

void LocalGraph::fill_sparse(const UndirectedGraph& graph) {
    // Local position of each candidate, looked up by binary search in the sorted ids.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> position(ids_.size());
    for (std::size_t a = 0; a < ids_.size(); ++a) {
        position[a] = {ids_[a], static_cast<std::uint32_t>(a)};
    }
    std::sort(position.begin(), position.end());
    for (std::size_t a = 0; a < ids_.size(); ++a) {
        for (std::uint32_t u : graph.neighbors[ids_[a]]) {
            const auto it = std::lower_bound(position.begin(), position.end(),
                                             std::make_pair(u, std::uint32_t{0}));
            if (it != position.end() && it->first == u) set(a, it->second);
        }
    }
}

bool any(const Word* set, std::size_t words) {
    for (std::size_t w = 0; w < words; ++w) {
        if (set[w] != 0) return true;
    }
    return false;
}

/// Recursive BBMC search. `level_sets_[d]` holds the candidate set at depth d.
class Searcher {
  public:
    Searcher(const LocalGraph& graph, std::uint32_t root, CliqueSearchState& state)
        : graph_(graph), root_(root), state_(state) {}

    void run() {
        std::vector<Word> all(graph_.words(), 0);
        for (std::size_t v = 0; v < graph_.size(); ++v) all[v / 64] |= Word{1} << (v % 64);
        expand(1, all);  // depth 1: the root is in the clique
    }

  private:
    /// Greedy sequential colouring of `set` (BBMC): vertices whose colour cannot beat the best
    /// clique are left out of `order`; the rest come with non-decreasing colours.
    void colour_sort(const std::vector<Word>& set, std::size_t kmin,
                     std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& colours) const {
        const std::size_t words = graph_.words();
        std::vector<Word> uncoloured = set;
        std::vector<Word> q(words);
        for (std::uint32_t k = 1; any(uncoloured.data(), words); ++k) {
            q = uncoloured;
            for (std::size_t w = 0; w < words; ++w) {
                while (q[w] != 0) {
                    const std::size_t v = w * 64 + static_cast<std::size_t>(std::countr_zero(q[w]));
                    q[w] &= q[w] - 1;
                    uncoloured[w] &= ~(Word{1} << (v % 64));
                    const Word* row = graph_.row(v);
                    for (std::size_t x = w; x < words; ++x) q[x] &= ~row[x];
                    if (k >= kmin) {
                        order.push_back(static_cast<std::uint32_t>(v));
                        colours.push_back(k);
                    }
                }
            }
        }
    }

    void record(std::size_t depth) {
        state_.best.assign(1, root_);
        for (std::size_t d = 0; d + 1 < depth; ++d)
            state_.best.push_back(graph_.global_id(current_[d]));
    }

    void expand(std::size_t depth, std::vector<Word> set) {
        if (state_.truncated) return;
        if (++state_.nodes > state_.max_nodes) {
            state_.truncated = true;
            return;
        }
        const std::size_t best = state_.best.size();
        const std::size_t kmin = best >= depth ? best - depth + 1 : 1;
        std::vector<std::uint32_t> order;
        std::vector<std::uint32_t> colours;
        colour_sort(set, kmin, order, colours);
        std::vector<Word> next(graph_.words());
        for (std::size_t i = order.size(); i-- > 0;) {
            if (depth + colours[i] <= state_.best.size() || state_.truncated) return;
            const std::uint32_t v = order[i];
            const Word* row = graph_.row(v);
            for (std::size_t w = 0; w < next.size(); ++w) next[w] = set[w] & row[w];
            current_.push_back(v);
            if (any(next.data(), next.size())) {
                expand(depth + 1, next);
            } else if (depth + 1 > state_.best.size()) {
                record(depth + 1);
            }
            current_.pop_back();
            set[v / 64] &= ~(Word{1} << (v % 64));
        }
    }

    const LocalGraph& graph_;
    std::uint32_t root_;
    CliqueSearchState& state_;
    std::vector<std::uint32_t> current_;
};

}  // namespace

DenseAdjacency::DenseAdjacency(const UndirectedGraph& graph)
    : words_((graph.num_vertices() + 63) / 64), bits_(graph.num_vertices() * words_, 0) {
    for (std::size_t a = 0; a < graph.num_vertices(); ++a) {
        for (std::uint32_t b : graph.neighbors[a])
            bits_[a * words_ + b / 64] |= Word{1} << (b % 64);
    }
}

void search_rooted_clique(const UndirectedGraph& graph, const DenseAdjacency* dense,
                          std::uint32_t root, const std::vector<std::uint32_t>& candidates,
                          CliqueSearchState& state) {
    if (candidates.empty()) {
        if (state.best.empty()) state.best.assign(1, root);
        return;
    }
    const LocalGraph local(graph, dense, candidates);
    Searcher(local, root, state).run();
}

}  // namespace scantling::registration::detail
