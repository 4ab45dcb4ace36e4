// accumulate: reads each wave item's radiance and shadow slots and the active-pixel list; for the
// j-th pixel touched by the wave, adds each of its samples in the wave, in sample order, to the
// pixel's running mean and M2 (sum of squared deviations from the mean) by Welford's update,
// compensated: mean and M2 are float-float pairs hi + lo (shared/ffloat.h), each update's
// increment (delta / n, delta * (x - mean')) is a float whose own rounding is relative to the
// increment, and its addition is exact; the sample count is a 64-bit integer. So the mean does not
// drift however many samples (a float32 mean stops moving once delta/n is below half an ulp, near
// 2^24 samples) and the count is exact past 2^32; the result is the same for any wave size, since
// every pixel's samples are added one by one in sample order. One work item per touched pixel: its
// runs of items (stage_common.h) in the wave, in order.
// Film state per pixel (four float4): mean = rgb hi part, w = count bits 0..31 (as_float);
// meanLo = rgb lo part, w = count bits 32..63; m2, m2Lo = M2's hi and lo parts, w = 0.
// With the sobol sampler's K > 1 sub-sequences (FrameParams::sobolSplits; sample s belongs to
// s % K), also split[K pixel + k]: sub-sequence k's running mean (rgb, float) and count (w, uint
// bits), from which the film estimates the error of the mean (image/film.h meanVariance).
#pragma once
#include "../shared/ffloat.h"
#include "stage_common.h"

MCL_INLINE void accumulate_item(const accumulate_args* a, uint j) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint shift = f->sampleBlockShift, ac = f->activeCount;
  if (j >= wave_touched_pixels(a->waveStart, a->waveCount, shift, ac)) return;
  uint pixel = a->active[(uint)(((a->waveStart >> shift) + j) % ac)];  // run q0 + j's
  ffloat4 mean = ff_make(a->mean[pixel], a->meanLo[pixel]);
  ffloat4 m2 = ff_make(a->m2[pixel], a->m2Lo[pixel]);
  ulong n = (ulong)as_uint(mean.hi.w) | ((ulong)as_uint(mean.lo.w) << 32);
  // The w lanes compute like the others: zero them (a count's bits as a float may be a denormal).
  mean.hi.w = 0.0f;
  mean.lo.w = 0.0f;
  const uint splits = f->sobolSplits;
  // Run q0 + j + m ac starts at item ((q0 + j + m ac) << shift) - waveStart (the first one may
  // start before the wave, the last may end after it).
  const ulong g0 = a->waveStart, g1 = g0 + a->waveCount;
  for (ulong q = (g0 >> shift) + j; (q << shift) < g1; q += ac) {
    uint first, end;
    wave_run_items(g0, a->waveCount, shift, q, &first, &end);
    for (uint i = first; i < end; ++i) {
      float4 value = a->radiance[i];
      for (uint k = 0; k < f->shadowSlots; ++k) value += a->shadowContrib[i * f->shadowSlots + k];
      value.w = 0.0f;
      if (f->sampler == MCL_SAMPLER_SOBOL && splits > 1u) {
        uint at = pixel * splits + item_sample(f, a->waveStart, i) % splits;
        float4 sub = a->split[at];
        uint c = as_uint(sub.w) + 1u;
        sub.w = 0.0f;
        sub += (value - sub) / (float)c;
        sub.w = as_float(c);
        a->split[at] = sub;
      }
      n += 1;
      float4 delta = (value - mean.hi) - mean.lo;
      mean = ff_add_float(mean, delta / (float)n);
      m2 = ff_add_float(m2, delta * ((value - mean.hi) - mean.lo));
    }
  }
  mean.hi.w = as_float((uint)(n & 0xfffffffful));
  mean.lo.w = as_float((uint)(n >> 32));
  a->mean[pixel] = mean.hi;
  a->meanLo[pixel] = mean.lo;
  a->m2[pixel] = m2.hi;
  a->m2Lo[pixel] = m2.lo;
}
