// accumulate: reads each wave item's radiance and shadow slots and the active-pixel list; for the
// j-th pixel touched by the wave, adds each of its samples in the wave, in sample order, to the
// pixel's running mean and M2 (sum of squared deviations from the mean) by Welford's update,
// compensated: mean and M2 are float-float pairs hi + lo (shared/ffloat.h), each update's
// increment (delta / n, delta * (x - mean')) is a float whose own rounding is relative to the
// increment, and its addition is exact; the sample count is a 64-bit integer. So the mean does not
// drift however many samples (a float32 mean stops moving once delta/n is below half an ulp, near
// 2^24 samples) and the count is exact past 2^32; the result is the same for any wave size, since
// every pixel's samples are added one by one in sample order. The body takes W consecutive touched
// pixels j, one per lane (W = MCL_LANES: 1 on the host backend and GPUs; lanes past the last
// touched pixel masked), each walking its runs of items (stage_common.h) in the wave in sample
// order, the lanes stepping together (a lane whose samples are done is masked). The film is
// gathered and scattered per lane (the active list may be any order; consecutive pixels: whole
// vector loads); with blocks of C samples per pixel a lane's C items are C consecutive items, the
// lanes' C apart: one float4 load per lane and step.
// Film state per pixel (four float4): mean = rgb hi part, w = count bits 0..31 (as_float);
// meanLo = rgb lo part, w = count bits 32..63; m2, m2Lo = M2's hi and lo parts, w = 0.
// With the sobol sampler's K > 1 sub-sequences (FrameParams::sobolSplits; sample s belongs to
// s % K), also split[K pixel + k]: sub-sequence k's running mean (rgb, float) and count (w, uint
// bits), from which the film estimates the error of the mean (image/film.h meanVariance).
#pragma once
#include "../shared/ffloat.h"
#include "stage_lanes.h"

// One sample's Welford update of one colour component (accumulate.h), for the lanes set in m.
MCL_INLINE void v_welford(vmask m, vfloat value, vfloat nf, vffloat* mean, vffloat* m2) {
  vfloat delta = (value - mean->hi) - mean->lo;
  vffloat meanNew = ff_add_float(*mean, delta / nf);
  vffloat m2New = ff_add_float(*m2, delta * ((value - meanNew.hi) - meanNew.lo));
  *mean = ff_select(m, meanNew, *mean);
  *m2 = ff_select(m, m2New, *m2);
}

// The radiance plus shadow slots of item i0 + k stride for each lane k (stride 1: whole vector loads).
MCL_INLINE void v_item_values(const accumulate_args* a, uint slots, uint i0, uint stride, vfloat* vx, vfloat* vy,
                              vfloat* vz) {
  MCL_GLOBAL const float* rad = (MCL_GLOBAL const float*)a->radiance;
  MCL_GLOBAL const float* sc = (MCL_GLOBAL const float*)a->shadowContrib;
  vfloat vw, sx, sy, sz, sw;
  if (stride == 1u) v_load4(rad + (ulong)i0 * 4, vx, vy, vz, &vw);
  else v_load4_stride(rad + (ulong)i0 * 4, stride * 4, vx, vy, vz, &vw);
  if (slots == 1 && stride == 1u) {  // AO
    v_load4(sc + (ulong)i0 * 4, &sx, &sy, &sz, &sw);
    *vx = *vx + sx;
    *vy = *vy + sy;
    *vz = *vz + sz;
  } else if (slots == 2 && stride == 1u) {  // direct lighting with one light sample
    vfloat tx, ty, tz, tw;
    v_load4_pairs(sc + (ulong)i0 * 8, &sx, &sy, &sz, &sw, &tx, &ty, &tz, &tw);
    *vx = *vx + sx + tx;
    *vy = *vy + sy + ty;
    *vz = *vz + sz + tz;
  } else {
    for (uint k = 0; k < slots; ++k) {
      v_load4_stride(sc + ((ulong)i0 * slots + k) * 4, stride * slots * 4, &sx, &sy, &sz, &sw);
      *vx = *vx + sx;
      *vy = *vy + sy;
      *vz = *vz + sz;
    }
  }
}

// A packet's pixels' film state (accumulate.h's four float4 per pixel) in lanes: the 64-bit sample
// count, mean and M2 as float-float pairs. run: the lanes' pixels are p0, p0 + 1, ... (whole vector
// loads and stores); otherwise per-lane gathers and scatters, of the first `lanes` lanes.
typedef struct {
  vulong n;
  vffloat meanX, meanY, meanZ, m2X, m2Y, m2Z, m2W;
} FilmLanes;

MCL_INLINE FilmLanes film_lanes_load(const accumulate_args* a, vuint pixel, int run, uint p0) {
  MCL_GLOBAL const float* film[4] = {(MCL_GLOBAL const float*)a->mean, (MCL_GLOBAL const float*)a->meanLo,
                                     (MCL_GLOBAL const float*)a->m2, (MCL_GLOBAL const float*)a->m2Lo};
  vfloat x[4], y[4], z[4], w[4];
  for (uint k = 0; k < 4u; ++k) {
    if (run) v_load4(film[k] + (ulong)p0 * 4, &x[k], &y[k], &z[k], &w[k]);
    else v_gather4(film[k], pixel, 4, &x[k], &y[k], &z[k], &w[k]);
  }
  FilmLanes fl;
  fl.n = v_cvt_ul_u(v_as_uint(w[0])) | (v_cvt_ul_u(v_as_uint(w[1])) << 32);
  fl.meanX = ff_make(x[0], x[1]);
  fl.meanY = ff_make(y[0], y[1]);
  fl.meanZ = ff_make(z[0], z[1]);
  fl.m2X = ff_make(x[2], x[3]);
  fl.m2Y = ff_make(y[2], y[3]);
  fl.m2Z = ff_make(z[2], z[3]);
  fl.m2W = ff_make(w[2], w[3]);
  return fl;
}

MCL_INLINE void film_lanes_store(const accumulate_args* a, vuint pixel, int run, uint p0, uint lanes,
                                 const FilmLanes* fl) {
  MCL_GLOBAL float* film[4] = {(MCL_GLOBAL float*)a->mean, (MCL_GLOBAL float*)a->meanLo, (MCL_GLOBAL float*)a->m2,
                               (MCL_GLOBAL float*)a->m2Lo};
  vfloat countLo = v_as_float(v_cvt_u_ul(fl->n & 0xfffffffful)), countHi = v_as_float(v_cvt_u_ul(fl->n >> 32));
  vfloat x[4] = {fl->meanX.hi, fl->meanX.lo, fl->m2X.hi, fl->m2X.lo};
  vfloat y[4] = {fl->meanY.hi, fl->meanY.lo, fl->m2Y.hi, fl->m2Y.lo};
  vfloat z[4] = {fl->meanZ.hi, fl->meanZ.lo, fl->m2Z.hi, fl->m2Z.lo};
  vfloat w[4] = {countLo, countHi, fl->m2W.hi, fl->m2W.lo};
  for (uint k = 0; k < 4u; ++k) {
    if (run) v_store4(film[k] + (ulong)p0 * 4, x[k], y[k], z[k], w[k]);
    else v_scatter4_n(film[k], pixel, 4, lanes, x[k], y[k], z[k], w[k]);
  }
}

// The general walk (run_walk: any block shift, any sub-sequence count, a partial packet of
// `lanes` lanes); the sub-sequence accumulators are updated lane by lane.
MCL_INLINE void accumulate_runs(const accumulate_args* a, uint j0, uint lanes) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint slots = f->shadowSlots;
  const uint splits = f->sampler == MCL_SAMPLER_SOBOL ? f->sobolSplits : 1u;
  const ulong g0 = a->waveStart;
  RunWalk walk;
  vuint pixel = run_walk_begin(&walk, f, a->active, g0, a->waveCount, j0, lanes);
  FilmLanes fl = film_lanes_load(a, pixel, 0, 0u);
  MCL_GLOBAL const float* rad = (MCL_GLOBAL const float*)a->radiance;
  MCL_GLOBAL const float* sc = (MCL_GLOBAL const float*)a->shadowContrib;
  for (vmask step = run_walk_step(&walk); v_any(step); step = run_walk_step(&walk)) {
    vuint i = walk.i;
    vuint at = vsel(step, i, v_u(0u));  // masked lanes read item 0
    vfloat vx, vy, vz, vw, sx, sy, sz, sw;
    v_gather4(rad, at, 4, &vx, &vy, &vz, &vw);
    for (uint k = 0; k < slots; ++k) {
      v_gather4(sc + k * 4, at, slots * 4, &sx, &sy, &sz, &sw);
      vx = vx + sx;
      vy = vy + sy;
      vz = vz + sz;
    }
    if (splits > 1u) {  // sub-sequence item_sample % K: sub += (value - sub) / c, lane by lane
      uint set[MCL_LANES] MCL_LANE_ALIGN, it[MCL_LANES] MCL_LANE_ALIGN, px[MCL_LANES] MCL_LANE_ALIGN;
      float x[MCL_LANES] MCL_LANE_ALIGN, y[MCL_LANES] MCL_LANE_ALIGN, z[MCL_LANES] MCL_LANE_ALIGN;
      v_store_lanes(v_mask01(step), set);
      v_store_lanes(i, it);
      v_store_lanes(pixel, px);
      v_store_lanes(vx, x);
      v_store_lanes(vy, y);
      v_store_lanes(vz, z);
      for (uint l = 0; l < MCL_LANES; ++l) {
        if (!set[l]) continue;
        uint s = px[l] * splits + item_sample(f, g0, it[l]) % splits;
        float4 sub = a->split[s];
        uint c = as_uint(sub.w) + 1u;
        sub.w = 0.0f;
        sub += (make_float4(x[l], y[l], z[l], 0.0f) - sub) / (float)c;
        sub.w = as_float(c);
        a->split[s] = sub;
      }
    }
    fl.n += v_cvt_ul_u(v_mask01(step));
    vfloat nf = v_cvt_f_ul(fl.n);
    v_welford(step, vx, nf, &fl.meanX, &fl.m2X);
    v_welford(step, vy, nf, &fl.meanY, &fl.m2Y);
    v_welford(step, vz, nf, &fl.meanZ, &fl.m2Z);
    // The w lanes compute like the others from value.w = 0 and mean.w = 0 (stage_accumulate).
    fl.m2W = ff_select(step, ff_add_float(fl.m2W, v_f(0.0f) * (v_f(0.0f) - v_f(0.0f) - v_f(0.0f))), fl.m2W);
    walk.i = i + v_mask01(step);
  }
  film_lanes_store(a, pixel, 0, 0u, lanes, &fl);
}

MCL_INLINE void stage_accumulate(const accumulate_args* a, uint j0) {
  MCL_CONSTANT const FrameParams* f = a->frame;
  const uint ac = f->activeCount, count = a->waveCount, shift = f->sampleBlockShift;
  const uint limit = wave_touched_pixels(a->waveStart, count, shift, ac);
  if (j0 >= limit) return;
  // Blocks of C = 2^shift samples per pixel: lane k's samples are items (j0 + k) C .. + C - 1, the
  // packet's when the wave starts a block, holds the W pixels' whole runs and no second run of any.
  const uint block = 1u << shift;
  const int blocks = shift != 0u && (a->waveStart & (block - 1u)) == 0u &&
                     ((ulong)j0 + MCL_LANES) * block <= count && ((ulong)j0 + ac) * block >= count;
  // The sobol sampler's K sub-sequence accumulators (accumulate.h): with blocks whose C samples
  // per lane start at a multiple of C, and K dividing C, step t of every lane updates
  // sub-sequence t % K, held in registers for the packet; otherwise the general walk (per lane, the
  // same bits).
  const uint splits = f->sampler == MCL_SAMPLER_SOBOL ? f->sobolSplits : 1u;
  if (v_packet_partial(j0, limit) || (splits > 1u && !(blocks && block % splits == 0u)) ||
      (shift != 0u && !blocks)) {
    accumulate_runs(a, j0, v_packet_lanes(j0, limit));
    return;
  }
  vuint pixel;
  if (blocks) {  // lane k: run q0 + j0 + k (ac >= W here, so at most one wrap)
    vuint r = (uint)(((a->waveStart >> shift) + j0) % ac) + v_lane_index();
    pixel = v_gather_uint(a->active, vsel(r >= ac, r - ac, r));
  } else {
    vuint sample;
    v_item_pixel_sample(f, a->active, a->waveStart, j0, &pixel, &sample);
  }
  // Consecutive pixels (the active list of a render without adaptive sampling): whole vector
  // loads and stores of the film; otherwise per-lane gathers and scatters.
  const uint p0 = v_first_lane(pixel);
  const int run = v_all(pixel == p0 + v_lane_index());
  FilmLanes fl = film_lanes_load(a, pixel, run, p0);
  const uint slots = f->shadowSlots;
  // Sub-sequence k of lane l: split[pixel_l K + k] (K <= C <= W here).
  vfloat subX[MCL_LANES], subY[MCL_LANES], subZ[MCL_LANES];
  vuint subN[MCL_LANES];
  MCL_GLOBAL float* split = (MCL_GLOBAL float*)a->split;
  for (uint k = 0; splits > 1u && k < splits; ++k) {
    vfloat w;
    v_gather4(split + k * 4u, pixel, splits * 4u, &subX[k], &subY[k], &subZ[k], &w);
    subN[k] = v_as_uint(w);
  }
  for (uint step = 0; blocks && step < block; ++step) {
    vfloat vx, vy, vz;
    v_item_values(a, slots, j0 * block + step, block, &vx, &vy, &vz);
    vmask live = v_lane_index() == v_lane_index();
    if (splits > 1u) {  // accumulate.h's sub-sequence update, sub += (value - sub) / c
      const uint k = step % splits;
      subN[k] = subN[k] + 1u;
      vfloat cf = v_cvt_f_u(subN[k]);
      subX[k] = subX[k] + (vx - subX[k]) / cf;
      subY[k] = subY[k] + (vy - subY[k]) / cf;
      subZ[k] = subZ[k] + (vz - subZ[k]) / cf;
    }
    fl.n += 1u;
    vfloat nf = v_cvt_f_ul(fl.n);
    v_welford(live, vx, nf, &fl.meanX, &fl.m2X);
    v_welford(live, vy, nf, &fl.meanY, &fl.m2Y);
    v_welford(live, vz, nf, &fl.meanZ, &fl.m2Z);
    fl.m2W = ff_add_float(fl.m2W, v_f(0.0f) * (v_f(0.0f) - v_f(0.0f) - v_f(0.0f)));  // as below
  }
  for (uint k = 0; splits > 1u && k < splits; ++k)
    v_scatter4(split + k * 4u, pixel, splits * 4u, subX[k], subY[k], subZ[k], v_as_float(subN[k]));
  MCL_GLOBAL const float* rad = (MCL_GLOBAL const float*)a->radiance;
  MCL_GLOBAL const float* sc = (MCL_GLOBAL const float*)a->shadowContrib;
  for (uint i0 = j0; !blocks && i0 < count; i0 += ac) {
    vuint i = i0 + v_lane_index();
    vmask live = i < count;
    vfloat vx, vy, vz, vw, sx, sy, sz, sw;
    if (count - i0 >= MCL_LANES) {  // the packet's items i0 .. i0 + W - 1 all exist
      v_item_values(a, slots, i0, 1u, &vx, &vy, &vz);
    } else {  // lanes past the wave read item i0 (and are masked)
      vuint at = vsel(live, i, v_u(i0));
      v_gather4(rad, at, 4, &vx, &vy, &vz, &vw);
      for (uint k = 0; k < slots; ++k) {
        v_gather4(sc + k * 4, at, slots * 4, &sx, &sy, &sz, &sw);
        vx = vx + sx;
        vy = vy + sy;
        vz = vz + sz;
      }
    }
    fl.n += v_cvt_ul_u(v_mask01(live));
    vfloat nf = v_cvt_f_ul(fl.n);
    v_welford(live, vx, nf, &fl.meanX, &fl.m2X);
    v_welford(live, vy, nf, &fl.meanY, &fl.m2Y);
    v_welford(live, vz, nf, &fl.meanZ, &fl.m2Z);
    // The w lanes compute like the others from value.w = 0 and mean.w = 0: the mean's stay 0 (then
    // hold the count), M2's add 0 * 0.
    vffloat m2WNew = ff_add_float(fl.m2W, v_f(0.0f) * (v_f(0.0f) - v_f(0.0f) - v_f(0.0f)));
    fl.m2W = ff_select(live, m2WNew, fl.m2W);
  }
  film_lanes_store(a, pixel, run, p0, MCL_LANES, &fl);
}
