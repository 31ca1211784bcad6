#include "hypothesis_cliques.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

namespace scantling::registration::detail {
namespace {

bool adjacent(const UndirectedGraph& graph, std::uint32_t a, std::uint32_t b) {
    const auto& list = graph.neighbors[a];
    return std::binary_search(list.begin(), list.end(), b);
}

/// Greedy clique through `root` among the vertices not `used`.
std::vector<std::uint32_t> greedy_clique(const UndirectedGraph& graph,
                                         const std::vector<std::uint32_t>& core,
                                         const std::vector<char>& used, std::uint32_t root) {
    std::vector<std::uint32_t> clique{root};
    std::vector<std::uint32_t> cand, next;
    for (std::uint32_t u : graph.neighbors[root]) {
        if (used[u] == 0) cand.push_back(u);
    }
    while (!cand.empty()) {
        const auto best = std::max_element(cand.begin(), cand.end(), [&](auto a, auto b) {
            return core[a] < core[b] || (core[a] == core[b] && a > b);
        });
        const std::uint32_t u = *best;
        clique.push_back(u);
        next.clear();
        for (std::uint32_t w : cand) {
            if (w != u && adjacent(graph, u, w)) next.push_back(w);
        }
        cand.swap(next);
    }
    std::sort(clique.begin(), clique.end());
    return clique;
}

}  // namespace

std::vector<std::vector<std::uint32_t>> disjoint_cliques(const UndirectedGraph& graph,
                                                         std::vector<std::uint32_t> first,
                                                         std::size_t count, std::size_t min_size) {
    std::vector<std::vector<std::uint32_t>> cliques;
    if (count == 0 || first.size() < min_size) return cliques;
    cliques.push_back(std::move(first));
    if (count == 1) return cliques;
    const std::vector<std::uint32_t> core = core_numbers(graph);
    std::vector<std::uint32_t> order(graph.num_vertices());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return core[a] > core[b]; });
    std::vector<char> used(graph.num_vertices(), 0);
    for (std::uint32_t v : cliques.front()) used[v] = 1;
    for (std::uint32_t v : order) {
        if (cliques.size() >= count || core[v] + 1 < min_size) break;
        if (used[v] != 0) continue;
        std::vector<std::uint32_t> clique = greedy_clique(graph, core, used, v);
        for (std::uint32_t u : clique) used[u] = 1;
        if (clique.size() >= min_size) cliques.push_back(std::move(clique));
    }
    return cliques;
}

}  // namespace scantling::registration::detail
