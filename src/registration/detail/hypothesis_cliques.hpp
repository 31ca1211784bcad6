#pragma once
/// @file
/// Candidate inlier sets for hypothesis verification (private to robust_registration.cpp): the
/// maximum clique, then greedy cliques grown from the highest-core vertices not yet used.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <scantling/registration/max_clique.hpp>

namespace scantling::registration::detail {

/// `first` (the maximum clique of `graph`), followed by up to `count` − 1 further cliques of at
/// least `min_size` vertices, vertex-disjoint from each other and from `first`. Each is grown
/// greedily (the PMC heuristic: add the unused common neighbour of largest core number, ties
/// lower index) from the unused vertex of largest core number (ties lower index): high-core
/// vertices sit in large consistent sets, i.e. in the other poses the matches support. Cost
/// O(V + E) for the core numbers plus O(degree · clique · log degree) per clique.
/// Deterministic; each clique ascending.
std::vector<std::vector<std::uint32_t>> disjoint_cliques(const UndirectedGraph& graph,
                                                         std::vector<std::uint32_t> first,
                                                         std::size_t count, std::size_t min_size);

}  // namespace scantling::registration::detail
