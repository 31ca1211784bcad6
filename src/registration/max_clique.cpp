#include <scantling/core/error.hpp>
#include <scantling/registration/max_clique.hpp>

#include <algorithm>
#include <iterator>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "detail/clique_search.hpp"

namespace scantling::registration {
namespace {

/// Core numbers and the peeling (degeneracy) order of Batagelj & Zaversnik (2003), O(V + E).
struct Peeling {
    std::vector<std::uint32_t> core;
    std::vector<std::uint32_t> order;     ///< vertices in the order they were peeled
    std::vector<std::uint32_t> position;  ///< inverse of order
};

/// Bucket sort of the vertices by degree: `bin[d]` is where degree-d vertices start.
std::vector<std::uint32_t> sort_by_degree(const std::vector<std::uint32_t>& degree, Peeling& p) {
    const std::uint32_t max_degree = *std::max_element(degree.begin(), degree.end());
    std::vector<std::uint32_t> bin(max_degree + 1, 0);
    for (std::uint32_t d : degree) ++bin[d];
    std::uint32_t start = 0;
    for (std::uint32_t& b : bin) start += std::exchange(b, start);
    for (std::uint32_t v = 0; v < degree.size(); ++v) {
        p.position[v] = bin[degree[v]]++;
        p.order[p.position[v]] = v;
    }
    for (std::uint32_t d = max_degree; d > 0; --d) bin[d] = bin[d - 1];
    bin[0] = 0;
    return bin;
}

Peeling peel(const UndirectedGraph& graph) {
    const auto n = static_cast<std::uint32_t>(graph.num_vertices());
    Peeling p;
    p.core.resize(n);
    p.order.resize(n);
    p.position.resize(n);
    if (n == 0) return p;
    for (std::uint32_t v = 0; v < n; ++v)
        p.core[v] = static_cast<std::uint32_t>(graph.neighbors[v].size());
    std::vector<std::uint32_t> bin = sort_by_degree(p.core, p);
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t v = p.order[i];
        for (std::uint32_t u : graph.neighbors[v]) {
            if (p.core[u] <= p.core[v]) continue;
            // Move u to the front of its degree bucket, then shrink its degree by one.
            const std::uint32_t du = p.core[u];
            const std::uint32_t pw = bin[du];
            const std::uint32_t w = p.order[pw];
            if (u != w) {
                std::swap(p.order[p.position[u]], p.order[pw]);
                std::swap(p.position[u], p.position[w]);
            }
            ++bin[du];
            --p.core[u];
        }
    }
    return p;
}

/// Greedy clique through `v`: repeatedly adds the candidate of largest core number (ties: lower
/// index) and keeps only its neighbours as candidates.
std::vector<std::uint32_t> greedy_clique(const UndirectedGraph& graph,
                                         const detail::DenseAdjacency* dense, const Peeling& p,
                                         std::uint32_t v, std::size_t min_core) {
    std::vector<std::uint32_t> clique{v};
    std::vector<std::uint32_t> cand;
    for (std::uint32_t u : graph.neighbors[v]) {
        if (p.core[u] >= min_core) cand.push_back(u);
    }
    std::vector<std::uint32_t> next;
    while (!cand.empty()) {
        const auto best = std::max_element(cand.begin(), cand.end(), [&](auto a, auto b) {
            return p.core[a] < p.core[b] || (p.core[a] == p.core[b] && a > b);
        });
        const std::uint32_t u = *best;
        clique.push_back(u);
        next.clear();
        if (dense != nullptr) {
            std::copy_if(cand.begin(), cand.end(), std::back_inserter(next),
                         [&](std::uint32_t w) { return dense->connected(u, w); });
        } else {
            std::set_intersection(cand.begin(), cand.end(), graph.neighbors[u].begin(),
                                  graph.neighbors[u].end(), std::back_inserter(next));
        }
        cand.swap(next);
    }
    return clique;
}

/// The PMC heuristic: greedy cliques from the highest-core vertices down, kept when larger; at
/// most `max_starts` of them (when an exact search follows, a few starts give it a good bound).
std::vector<std::uint32_t> greedy_max_clique(const UndirectedGraph& graph,
                                             const detail::DenseAdjacency* dense, const Peeling& p,
                                             std::size_t max_starts) {
    std::vector<std::uint32_t> best{0};
    std::size_t starts = 0;
    for (std::size_t i = p.order.size(); i-- > 0 && starts < max_starts;) {
        const std::uint32_t v = p.order[i];
        if (p.core[v] + 1 <= best.size()) continue;
        ++starts;
        auto clique = greedy_clique(graph, dense, p, v, best.size());
        if (clique.size() > best.size()) best = std::move(clique);
    }
    return best;
}

/// Later neighbours of `v` in the peeling order that may be in a clique larger than `best`.
std::vector<std::uint32_t> later_candidates(const UndirectedGraph& graph, const Peeling& p,
                                            std::uint32_t v, std::size_t best) {
    std::vector<std::uint32_t> cand;
    for (std::uint32_t u : graph.neighbors[v]) {
        if (p.position[u] > p.position[v] && p.core[u] >= best) cand.push_back(u);
    }
    return cand;
}

}  // namespace

std::size_t UndirectedGraph::num_edges() const {
    std::size_t twice = 0;
    for (const auto& list : neighbors) twice += list.size();
    return twice / 2;
}

UndirectedGraph graph_from_edges(std::size_t num_vertices,
                                 std::span<const std::pair<std::uint32_t, std::uint32_t>> edges) {
    UndirectedGraph graph;
    graph.neighbors.resize(num_vertices);
    for (std::size_t k = 0; k < edges.size(); ++k) {
        const auto [a, b] = edges[k];
        if (a == b || a >= num_vertices || b >= num_vertices) {
            throw InputError(
                fmt::format("graph_from_edges: edge {} = ({}, {}) is a self-loop or "
                            "out of range, expected two distinct vertices < {}",
                            k, a, b, num_vertices));
        }
        graph.neighbors[a].push_back(b);
        graph.neighbors[b].push_back(a);
    }
    for (auto& list : graph.neighbors) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
    }
    return graph;
}

std::vector<std::uint32_t> core_numbers(const UndirectedGraph& graph) { return peel(graph).core; }

std::string_view to_string(MaxCliqueMethod method) {
    switch (method) {
        case MaxCliqueMethod::kExact:
            return "exact";
        case MaxCliqueMethod::kTruncated:
            return "truncated";
        case MaxCliqueMethod::kGreedy:
            return "greedy";
    }
    return "unknown";
}

void MaxCliqueConfig::validate(std::string_view prefix) const {
    if (max_vertices_exact < 1) {
        throw ConfigError(fmt::format("{}.max_vertices_exact = 0, expected >= 1", prefix));
    }
    if (max_search_nodes < 1) {
        throw ConfigError(fmt::format("{}.max_search_nodes = 0, expected >= 1", prefix));
    }
}

MaxCliqueResult find_max_clique(const UndirectedGraph& graph, const MaxCliqueConfig& config) {
    config.validate();
    MaxCliqueResult result;
    if (graph.num_vertices() == 0) return result;
    const Peeling p = peel(graph);
    result.degeneracy = *std::max_element(p.core.begin(), p.core.end());
    std::optional<detail::DenseAdjacency> dense;
    if (graph.num_vertices() <= detail::DenseAdjacency::kMaxDenseVertices) dense.emplace(graph);
    const detail::DenseAdjacency* dense_ptr = dense ? &*dense : nullptr;
    detail::CliqueSearchState state;
    // The exact search finds large cliques from its first roots anyway; the greedy bound only
    // needs to be good, not best (64 starts: a fraction of the search time on real graphs).
    const std::size_t starts = config.solve_exactly ? 64 : graph.num_vertices();
    state.best = greedy_max_clique(graph, dense_ptr, p, starts);
    state.max_nodes = config.max_search_nodes;
    const auto survivors = static_cast<std::size_t>(std::count_if(
        p.core.begin(), p.core.end(), [&](std::uint32_t c) { return c >= state.best.size(); }));
    result.method = MaxCliqueMethod::kGreedy;
    if (config.solve_exactly && survivors <= config.max_vertices_exact) {
        for (std::size_t i = p.order.size(); i-- > 0 && !state.truncated;) {
            const std::uint32_t v = p.order[i];
            if (p.core[v] + 1 <= state.best.size()) continue;
            const auto cand = later_candidates(graph, p, v, state.best.size());
            if (cand.size() + 1 <= state.best.size()) continue;
            detail::search_rooted_clique(graph, dense_ptr, v, cand, state);
        }
        result.method = state.truncated ? MaxCliqueMethod::kTruncated : MaxCliqueMethod::kExact;
    }
    result.search_nodes = state.nodes;
    result.vertices = std::move(state.best);
    std::sort(result.vertices.begin(), result.vertices.end());
    return result;
}

}  // namespace scantling::registration
