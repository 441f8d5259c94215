// Private to the CPU multi-resolution kernel (MultiresolutionKernel.cpp, its only includer): the cells whose spread
// meets two or three shells, each split into one piece per shell (addPieces, and four cells at a time in the AVX2
// build).
#pragma once

#include "MultiresolutionSampleAdds.h"

#include "gls/MultiresolutionKernel.h"

#include <cstddef>
#include <cstdint>
#if GLS_KERNEL_DISPATCH
#include <immintrin.h>
#endif

namespace gls
{
namespace kernel
{

/// The cells `list[0, count)` whose spread meets at most `Pieces` shells from its first one (cellShell): each adds
/// `Pieces` pieces [lo, sq[k]], [sq[k], sq[k + 1]], ..., cut to [lo, min(hi, r2)] (pieceShare; shells past the
/// last one are clamped to it, with an empty piece, which adds zeros).
template <int Pieces, typename Set>
GLS_FORCE_INLINE void addPieces(const ScaleBinning& b, double r2, const std::uint32_t* list, std::size_t count,
  const MultiresolutionScratchT<Set>& s, AggregateMomentsT<Set>* bins)
{
  const int S = b.count;
  const double* sq = b.squaredScales;
  for (std::size_t i = 0; i < count; ++i)
  {
    const std::uint32_t c = list[i];
    const CellSampleT<Set>& sample = s.packedCells[c].sample;
    const double mean = s.cellMean[c], a = s.placements.halfWidth[c];
    const SpreadDensity density = s.placements.density(c);
    const double lo = mean - a, top = mean + a < r2 ? mean + a : r2;
    const int k = s.cellShell[c];
    double u = lo;
    for (int j = 0; j < Pieces; ++j)
    {
      const int shell = k + j < S ? k + j : S - 1;
      const double edge = k + j < S ? sq[k + j] : r2;
      const double w = edge < top ? edge : top;
      const double v = w > u ? w : u;
      addPackedCellShare(bins[shell], sample, pieceShare(mean, density, u, v));
      u = v;
    }
  }
}

#if GLS_KERNEL_DISPATCH
/// Four cells' spreads as the AVX2 piece loops read them (gathered from the classification's and the placements'
/// arrays): mean squared distance, density, lower end, top (the upper end, at most r2) and first shell.
struct SpreadLanes
{
  __m256d mean, rho, gradientScale, lo, top;
  __m128i shell;
};

__attribute__((target("avx2,fma"))) GLS_FORCE_INLINE SpreadLanes gatherSpreads(
  const MultiresolutionWalkScratch& s, const std::uint32_t* cells, double r2)
{
  const __m128i index = _mm_loadu_si128(reinterpret_cast<const __m128i*>(cells));
  SpreadLanes l;
  l.mean = _mm256_i32gather_pd(s.cellMean.data(), index, 8);
  const __m256d a = _mm256_i32gather_pd(s.placements.halfWidth.data(), index, 8);
  l.rho = _mm256_i32gather_pd(s.placements.rho.data(), index, 8);
  l.gradientScale = _mm256_i32gather_pd(s.placements.gradientScale.data(), index, 8);
  l.shell = _mm_i32gather_epi32(s.cellShell.data(), index, 4);
  l.lo = _mm256_sub_pd(l.mean, a);
  l.top = _mm256_min_pd(_mm256_add_pd(l.mean, a), _mm256_set1_pd(r2));
  return l;
}

/// pieceShare of the pieces [u, v] of four spreads (its arithmetic lane by lane, with multiply-adds), stored as
/// share[0..2] = m, share[3..5] = c, one lane per cell.
__attribute__((target("avx2,fma"))) GLS_FORCE_INLINE void pieceSharesAvx2(
  const SpreadLanes& l, __m256d u, __m256d v, double (*share)[4])
{
  const __m256d half = _mm256_set1_pd(0.5), third = _mm256_set1_pd(1.0 / 3.0), quarter = _mm256_set1_pd(0.25);
  const __m256d mean = l.mean;
  const __m256d d0 = _mm256_sub_pd(u, mean), d1 = _mm256_sub_pd(v, mean);
  const __m256d width = _mm256_sub_pd(v, u);
  const __m256d sum01 = _mm256_add_pd(d1, d0);
  const __m256d i1 = _mm256_mul_pd(_mm256_mul_pd(width, sum01), half);
  const __m256d q2 = _mm256_fmadd_pd(d1, d1, _mm256_fmadd_pd(d1, d0, _mm256_mul_pd(d0, d0)));
  const __m256d i2 = _mm256_mul_pd(_mm256_mul_pd(width, q2), third);
  const __m256d s2 = _mm256_fmadd_pd(d1, d1, _mm256_mul_pd(d0, d0));
  const __m256d i3 = _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(width, sum01), s2), quarter);
  const __m256d wr = _mm256_mul_pd(width, l.rho);
  const __m256d vu = _mm256_fmadd_pd(v, v, _mm256_fmadd_pd(v, u, _mm256_mul_pd(u, u)));
  const __m256d g = l.gradientScale;
  _mm256_store_pd(share[0], wr);
  _mm256_store_pd(share[1], _mm256_mul_pd(_mm256_mul_pd(wr, _mm256_add_pd(v, u)), half));
  _mm256_store_pd(share[2], _mm256_mul_pd(_mm256_mul_pd(wr, vu), third));
  _mm256_store_pd(share[3], _mm256_mul_pd(g, i1));
  _mm256_store_pd(share[4], _mm256_mul_pd(g, _mm256_fmadd_pd(mean, i1, i2)));
  const __m256d twoMean = _mm256_add_pd(mean, mean);
  const __m256d cubic = _mm256_fmadd_pd(_mm256_mul_pd(mean, mean), i1, _mm256_fmadd_pd(twoMean, i2, i3));
  _mm256_store_pd(share[5], _mm256_mul_pd(g, cubic));
}

/// addPieces four cells at a time (AVX2): the pieces' bounds and shares formed for four cells in vector registers,
/// then each cell's pieces added to its shells. The tail of fewer than four cells goes through addPieces.
template <int Pieces, typename Set>
__attribute__((target("avx2,fma"))) inline void addPiecesAvx2(const ScaleBinning& b, double r2,
  const std::uint32_t* list, std::size_t count, const MultiresolutionScratchT<Set>& s, AggregateMomentsT<Set>* bins)
{
  const __m256d vr2 = _mm256_set1_pd(r2);
  const __m128i lastShell = _mm_set1_epi32(b.count - 1);
  alignas(32) double shares[Pieces][6][4];
  alignas(16) int shells[Pieces][4];
  std::size_t i = 0;
  for (; i + 4 <= count; i += 4)
  {
    const SpreadLanes l = gatherSpreads(s, list + i, r2);
    __m256d u = l.lo;
    for (int j = 0; j < Pieces; ++j)
    {
      // addPieces' bounds: shells past the last one clamped to it, with an empty piece.
      const __m128i kj = _mm_add_epi32(l.shell, _mm_set1_epi32(j));
      const __m128i shell = _mm_min_epi32(kj, lastShell);
      const __m256d past = _mm256_castsi256_pd(_mm256_cvtepi32_epi64(_mm_cmpgt_epi32(kj, lastShell)));
      const __m256d edge = _mm256_blendv_pd(_mm256_i32gather_pd(b.squaredScales, shell, 8), vr2, past);
      const __m256d v = _mm256_max_pd(_mm256_min_pd(edge, l.top), u);
      pieceSharesAvx2(l, u, v, shares[j]);
      _mm_store_si128(reinterpret_cast<__m128i*>(shells[j]), shell);
      u = v;
    }
    for (int lane = 0; lane < 4; ++lane)
    {
      // The cell's F and H loaded once for all its pieces.
      const LoadedSampleT<Set> f = loadSample(s.packedCells[list[i + static_cast<std::size_t>(lane)]].sample);
      for (int j = 0; j < Pieces; ++j)
      {
        const double(&share)[6][4] = shares[j];
        addPackedCellShare(bins[shells[j][lane]], f,
          ShellShare{ { share[0][lane], share[1][lane], share[2][lane] },
            { share[3][lane], share[4][lane], share[5][lane] } });
      }
    }
  }
  addPieces<Pieces, Set>(b, r2, list + i, count - i, s, bins);
}
#endif

} // namespace kernel
} // namespace gls
