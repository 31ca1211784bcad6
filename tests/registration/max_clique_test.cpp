#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include <scantling/core/error.hpp>
#include <scantling/core/random.hpp>
#include <scantling/registration/max_clique.hpp>

namespace scantling::registration {
namespace {

using Edges = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

Edges random_edges(std::uint32_t n, double density, Rng& rng) {
    Edges edges;
    for (std::uint32_t a = 0; a < n; ++a) {
        for (std::uint32_t b = a + 1; b < n; ++b) {
            if (rng.uniform() < density) edges.emplace_back(a, b);
        }
    }
    return edges;
}

/// Size of the largest clique by enumerating every vertex subset (n <= 20).
std::size_t brute_force_clique_size(const UndirectedGraph& g) {
    const auto n = static_cast<std::uint32_t>(g.num_vertices());
    std::vector<std::uint32_t> adj(n, 0);
    for (std::uint32_t v = 0; v < n; ++v) {
        for (std::uint32_t u : g.neighbors[v]) adj[v] |= 1u << u;
    }
    std::size_t best = 0;
    for (std::uint32_t mask = 1; mask < (1u << n); ++mask) {
        const auto size = static_cast<std::size_t>(__builtin_popcount(mask));
        if (size <= best) continue;
        bool clique = true;
        for (std::uint32_t v = 0; v < n && clique; ++v) {
            if ((mask >> v & 1u) && ((adj[v] | (1u << v)) & mask) != mask) clique = false;
        }
        if (clique) best = size;
    }
    return best;
}

bool is_clique(const UndirectedGraph& g, const std::vector<std::uint32_t>& vertices) {
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        for (std::size_t j = i + 1; j < vertices.size(); ++j) {
            const auto& list = g.neighbors[vertices[i]];
            if (!std::binary_search(list.begin(), list.end(), vertices[j])) return false;
        }
    }
    return true;
}

TEST(MaxClique, MatchesBruteForceOnSmallRandomGraphs) {
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        for (double density : {0.2, 0.5, 0.8, 0.95}) {
            Rng rng(seed);
            const std::uint32_t n = seed <= 2 ? 20 : 8 + static_cast<std::uint32_t>(seed);
            const Edges edges = random_edges(n, density, rng);
            const UndirectedGraph g = graph_from_edges(n, edges);
            const MaxCliqueResult r = find_max_clique(g);
            EXPECT_EQ(r.method, MaxCliqueMethod::kExact);
            EXPECT_TRUE(is_clique(g, r.vertices));
            EXPECT_EQ(r.vertices.size(), brute_force_clique_size(g))
                << "seed " << seed << ", density " << density;
            EXPECT_TRUE(std::is_sorted(r.vertices.begin(), r.vertices.end()));
        }
    }
}

TEST(MaxClique, FindsPlantedCliqueInSparseGraph) {
    Rng rng(42);
    constexpr std::uint32_t kN = 400;
    Edges edges = random_edges(kN, 0.1, rng);
    std::vector<std::uint32_t> planted = {3,   17,  40,  41,  99,  120, 121, 150, 200, 201,
                                          222, 250, 251, 280, 300, 310, 333, 350, 380, 399};
    for (std::size_t i = 0; i < planted.size(); ++i) {
        for (std::size_t j = i + 1; j < planted.size(); ++j)
            edges.emplace_back(planted[i], planted[j]);
    }
    const UndirectedGraph g = graph_from_edges(kN, edges);
    const MaxCliqueResult r = find_max_clique(g);
    EXPECT_EQ(r.method, MaxCliqueMethod::kExact);
    EXPECT_EQ(r.vertices, planted);  // G(400, 0.1) alone has cliques of ~5
    EXPECT_GE(r.degeneracy, planted.size() - 1);
}

TEST(MaxClique, GreedyModeReturnsAClique) {
    Rng rng(5);
    const UndirectedGraph g = graph_from_edges(60, random_edges(60, 0.5, rng));
    MaxCliqueConfig config;
    config.solve_exactly = false;
    const MaxCliqueResult r = find_max_clique(g, config);
    EXPECT_EQ(r.method, MaxCliqueMethod::kGreedy);
    EXPECT_EQ(r.search_nodes, 0u);
    EXPECT_TRUE(is_clique(g, r.vertices));
    EXPECT_GE(r.vertices.size(), 3u);
}

TEST(MaxClique, NodeBudgetTruncatesToTheBestCliqueFound) {
    Rng rng(6);
    const UndirectedGraph g = graph_from_edges(80, random_edges(80, 0.6, rng));
    MaxCliqueConfig config;
    config.max_search_nodes = 3;
    const MaxCliqueResult truncated = find_max_clique(g, config);
    EXPECT_EQ(truncated.method, MaxCliqueMethod::kTruncated);
    EXPECT_TRUE(is_clique(g, truncated.vertices));
    const MaxCliqueResult exact = find_max_clique(g);
    EXPECT_EQ(exact.method, MaxCliqueMethod::kExact);
    EXPECT_LE(truncated.vertices.size(), exact.vertices.size());
}

TEST(MaxClique, TooManyVerticesFallsBackToGreedy) {
    Rng rng(8);
    const UndirectedGraph g = graph_from_edges(50, random_edges(50, 0.5, rng));
    MaxCliqueConfig config;
    config.max_vertices_exact = 5;
    EXPECT_EQ(find_max_clique(g, config).method, MaxCliqueMethod::kGreedy);
}

TEST(MaxClique, EmptyAndEdgelessGraphs) {
    EXPECT_TRUE(find_max_clique(UndirectedGraph{}).vertices.empty());
    const UndirectedGraph edgeless = graph_from_edges(4, Edges{});
    EXPECT_EQ(find_max_clique(edgeless).vertices, std::vector<std::uint32_t>{0});
}

TEST(MaxClique, CoreNumbersOfCliqueWithPendant) {
    // K4 on {0, 1, 2, 3} plus the pendant edge 3–4 and the isolated vertex 5.
    const Edges edges = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}, {3, 4}};
    const UndirectedGraph g = graph_from_edges(6, edges);
    EXPECT_EQ(core_numbers(g), (std::vector<std::uint32_t>{3, 3, 3, 3, 1, 0}));
    EXPECT_EQ(g.num_edges(), 7u);
    EXPECT_EQ(find_max_clique(g).vertices, (std::vector<std::uint32_t>{0, 1, 2, 3}));
}

TEST(MaxClique, GraphFromEdgesMergesDuplicatesAndRejectsBadEdges) {
    const Edges duplicated = {{0, 1}, {1, 0}, {0, 1}};
    EXPECT_EQ(graph_from_edges(2, duplicated).num_edges(), 1u);
    const Edges self_loop = {{1, 1}};
    EXPECT_THROW(graph_from_edges(2, self_loop), InputError);
    const Edges out_of_range = {{0, 2}};
    EXPECT_THROW(graph_from_edges(2, out_of_range), InputError);
}

TEST(MaxClique, RejectsBadConfig) {
    MaxCliqueConfig config;
    config.max_search_nodes = 0;
    EXPECT_THROW(find_max_clique(UndirectedGraph{}, config), ConfigError);
    config = {};
    config.max_vertices_exact = 0;
    EXPECT_THROW(find_max_clique(UndirectedGraph{}, config), ConfigError);
}

}  // namespace
}  // namespace scantling::registration
