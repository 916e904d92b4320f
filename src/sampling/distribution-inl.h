// Sampling a Distribution2D and its density, written once over lanes: LightSet runs the
// one-lane instances, the wavefront's kernels the same formulas in SIMD lanes, where each
// binary search's loads are gathers and many searches' cache misses overlap. Per-target
// header, see math/lanes-inl.h.
#if defined(WAVETRACE_SAMPLING_DISTRIBUTION_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_SAMPLING_DISTRIBUTION_INL_H_
#undef WAVETRACE_SAMPLING_DISTRIBUTION_INL_H_
#else
#define WAVETRACE_SAMPLING_DISTRIBUTION_INL_H_
#endif

#include "math/lanes-inl.h"
#include "sampling/distribution.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// The density on [0, 1) of entry i of n whose running sums are sums[i] and sums[i + 1], of
// total sums[n]: n (sums[i + 1] - sums[i]) / sums[n].
template <class L>
HWY_INLINE typename L::F EntryDensity(typename L::F before,
                                      typename L::F after,
                                      typename L::F total,
                                      int n) {
    return (after - before) * L::Set(static_cast<float>(n)) / total;
}

// The entry of n that x in [0, 1) falls in (0 for x below 0 or not a number).
template <class L>
HWY_INLINE typename L::I EntryAt(typename L::F x, int n) {
    const typename L::F zero = L::Set(0.0f);
    const typename L::F scaled = L::Select(x > zero, x, zero) * L::Set(static_cast<float>(n));
    return L::Trunc(L::Min(scaled, L::Set(static_cast<float>(n - 1))));
}

// A continuous sample in [0, 1) of the piecewise-constant density over n entries whose running
// sums start at sums[first] (n + 1 of them, from 0), with the guide of g cells that starts at
// guide[guide_first] (Distribution2DTables): the entry i is the last with sums[i] <= u sums[n],
// found by a binary search between the guide's entries for u's cell, as long as its widest range
// in any lane; the sample is (i + (u sums[n] - sums[i]) / (sums[i + 1] - sums[i])) / n, below 1.
// Returns its density, sets *index to first + i.
template <class L>
HWY_INLINE typename L::F SampleSums(const float* sums,
                                    typename L::I first,
                                    int n,
                                    const int32_t* guide,
                                    typename L::I guide_first,
                                    int g,
                                    typename L::F u,
                                    typename L::F* x,
                                    typename L::I* index) {
    using F = typename L::F;
    using I = typename L::I;
    const F total = L::Gather(sums, L::AddI(first, L::SetI(n)));
    const F target = u * total;
    // u g is exact (g a power of two): u lies in [cell / g, (cell + 1) / g), so its target lies
    // between those of the cell's two cutpoints, and its entry between theirs.
    const I cell = L::AddI(guide_first, EntryAt<L>(u, g));
    const I lo = L::GatherI(guide, cell), hi = L::GatherI(guide, L::AddI(cell, L::SetI(1)));
    I base = L::AddI(first, lo);
    I size = L::AddI(L::SubI(hi, lo), L::SetI(1));
    // Lanes down to one entry halve nothing: their base stays.
    while (L::AnyAbove(size, 1)) {
        const I half = L::HalfI(size);
        const I mid = L::AddI(base, half);
        base = L::SelectI(L::Gather(sums, mid) <= target, mid, base);
        size = L::SubI(size, half);
    }
    const F before = L::Gather(sums, base), after = L::Gather(sums, L::AddI(base, L::SetI(1)));
    const F within = (target - before) / (after - before);
    const F i = L::ToFloat(L::SubI(base, first));
    *x = L::Min((i + within) / L::Set(static_cast<float>(n)), L::Set(0x1.fffffep-1f));
    *index = base;
    return EntryDensity<L>(before, after, total, n);
}

// The two steps of a sample (u, v) in [0, 1)^2 of the distribution from the uniform u1, u2: v
// from the marginal, its density, and the row it falls in; then u from that row, its density.
// A caller with many samples may run the first step for all of them before the second, so that
// their rows' cache misses overlap.
template <class L>
HWY_INLINE typename L::F SampleMarginal(const Distribution2DTables& t,
                                        typename L::F u2,
                                        typename L::F* v,
                                        typename L::I* row) {
    return SampleSums<L>(t.marginal, L::SetI(0), t.nv, t.marginal_guide, L::SetI(0), t.gv, u2, v,
                         row);
}
// Where row `row`'s running sums and its guide start in the conditional tables.
template <class L>
HWY_INLINE typename L::I RowSums(const Distribution2DTables& t, typename L::I row) {
    return L::MulI(row, L::SetI(t.nu + 1));
}
template <class L>
HWY_INLINE typename L::I RowGuide(const Distribution2DTables& t, typename L::I row) {
    return L::MulI(row, L::SetI(t.gu + 1));
}
template <class L>
HWY_INLINE typename L::F SampleConditional(const Distribution2DTables& t,
                                           typename L::I row,
                                           typename L::F u1,
                                           typename L::F* u) {
    typename L::I column;
    return SampleSums<L>(t.conditional, RowSums<L>(t, row), t.nu, t.conditional_guide,
                         RowGuide<L>(t, row), t.gu, u1, u, &column);
}

// For a caller that takes many samples' second steps after their first (whose misses then
// overlap): what SampleConditional will read for row `row` and u1, fetched ahead. First the
// row's guide cell and total; then, once those have arrived, the sums the search starts
// between.
template <class L>
HWY_INLINE void PrefetchConditionalGuide(const Distribution2DTables& t,
                                         typename L::I row,
                                         typename L::F u1) {
    L::Prefetch(t.conditional_guide, L::AddI(RowGuide<L>(t, row), EntryAt<L>(u1, t.gu)));
    L::Prefetch(t.conditional, L::AddI(RowSums<L>(t, row), L::SetI(t.nu)));
}
template <class L>
HWY_INLINE void PrefetchConditionalSums(const Distribution2DTables& t,
                                        typename L::I row,
                                        typename L::F u1) {
    using I = typename L::I;
    const I cell = L::AddI(RowGuide<L>(t, row), EntryAt<L>(u1, t.gu));
    const I first = RowSums<L>(t, row);
    L::Prefetch(t.conditional, L::AddI(first, L::GatherI(t.conditional_guide, cell)));
    L::Prefetch(t.conditional,
                L::AddI(first, L::GatherI(t.conditional_guide, L::AddI(cell, L::SetI(1)))));
}

// For a caller that asks many densities after this (Distribution2DPdf): the entries of (u, v)
// in the conditional sums fetched ahead (the marginal is small: it stays in cache).
template <class L>
HWY_INLINE void PrefetchDistribution2DPdf(const Distribution2DTables& t,
                                          typename L::F u,
                                          typename L::F v) {
    L::Prefetch(t.conditional, L::AddI(RowSums<L>(t, EntryAt<L>(v, t.nv)), EntryAt<L>(u, t.nu)));
}

// Both steps; returns the density on the unit square.
template <class L>
HWY_INLINE typename L::F SampleDistribution2D(const Distribution2DTables& t,
                                              typename L::F u1,
                                              typename L::F u2,
                                              typename L::F* u,
                                              typename L::F* v) {
    typename L::I row;
    const typename L::F pdf_v = SampleMarginal<L>(t, u2, v, &row);
    return pdf_v * SampleConditional<L>(t, row, u1, u);
}

// The density of the distribution at (u, v).
template <class L>
HWY_INLINE typename L::F Distribution2DPdf(const Distribution2DTables& t,
                                           typename L::F u,
                                           typename L::F v) {
    using I = typename L::I;
    const I one = L::SetI(1);
    const I row = EntryAt<L>(v, t.nv);
    const typename L::F pdf_v =
        EntryDensity<L>(L::Gather(t.marginal, row), L::Gather(t.marginal, L::AddI(row, one)),
                        L::Set(t.marginal[t.nv]), t.nv);
    const I first = RowSums<L>(t, row);
    const I column = L::AddI(first, EntryAt<L>(u, t.nu));
    const typename L::F pdf_u = EntryDensity<L>(
        L::Gather(t.conditional, column), L::Gather(t.conditional, L::AddI(column, one)),
        L::Gather(t.conditional, L::AddI(first, L::SetI(t.nu))), t.nu);
    return pdf_v * pdf_u;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SAMPLING_DISTRIBUTION_INL_H_
