// types.h: every struct shared by the host and the kernels, defined once. Only float4, float, uint
// fields, explicit padding, 16-byte alignment; the C++ side checks sizes and offsets below, and a
// test launches a probe kernel that reports the device's view of them.
#pragma once
#include "compat.h"

#define MCL_NO_HIT 0xffffffffu
#define MCL_BVH_STACK_SIZE 64
#define MCL_AO_UNIFORM 0u
#define MCL_AO_COSINE 1u
#define MCL_DIRECT_LIGHT 0u
#define MCL_DIRECT_BRDF 1u
#define MCL_DIRECT_MIS 2u
// FrameParams::filterKind (camera.h's filter_offset): the pixel filter, drawn from by its inverse CDF.
#define MCL_FILTER_BOX 0u       // uniform over [-radius, radius]
#define MCL_FILTER_TRIANGLE 1u  // tent of half-width radius, closed-form inverse
#define MCL_FILTER_TABLE 2u     // tabulated (gaussian, mitchell, lanczos): FrameParams::filterCdf
#define MCL_FILTER_BINS 64
// FrameParams::sampler (shared/sampler.h): where the stages' uniform numbers come from.
#define MCL_SAMPLER_INDEPENDENT 0u  // pcg4d hash per (seed, pixel, sample, group): i.i.d.
#define MCL_SAMPLER_SOBOL 1u        // Owen-scrambled Sobol, one 4D set per group (shared/sobol.h)
// First-hit AOVs: float4s per wave item (record_aov.h) and per pixel sum (accumulate_aov.h, Film::aovSum):
// [0] (albedo, depth), [1] (shading normal, 0), [2] (emission seen directly, 0).
#define MCL_AOV_VECTORS 3

// Flattened BVH node (32 bytes). Interior: triCount == 0 and leftFirst is the left child; the right
// child is leftFirst + 1. Leaf: triCount > 0 triangles starting at leftFirst.
typedef struct MCL_ALIGN16 {
  float minX, minY, minZ;
  uint leftFirst;
  float maxX, maxY, maxZ;
  uint triCount;
} BvhNode;

// 8-wide BVH node (224 bytes), collapsed from the binary tree: what the wide traversal reads. The
// child boxes are SoA rows (lane i = child i) in the order minX, maxX, minY, maxY, minZ, maxZ, so a
// ray picks its near/far row per axis by index once and tests all eight boxes with float8
// arithmetic (one AVX register per row). child[i]: an interior child is the index of its wide
// node; a leaf has MCL_WIDE_LEAF set, its first triangle in bits 4..30 and count - 1 in bits 0..3.
// An empty slot has an empty box (min +inf, max -inf), which no ray enters. The child refs are uint
// fields, never float lanes: integer bits through float arithmetic are denormals. Rows are float
// arrays (vload8 on the device), so the host needs no float8 type; 224 = 7 * 32 bytes, and host
// arrays are 32-byte aligned (alignas: C++17's aligned new), so in the buffers CPU devices use in
// place no row straddles a cache line (with malloc's 16 bytes half of them did: Sponza direct
// 3% more CPU).
#define MCL_WIDE_WIDTH 8
#define MCL_WIDE_LEAF 0x80000000u
#define MCL_WIDE_EMPTY 0xffffffffu
// A wide level pushes at most 7 children and visits the eighth; no leaf is deeper than 63 levels.
#define MCL_WIDE_STACK_SIZE 448
typedef struct MCL_ALIGN32 {
  float bounds[6][8];  // minX, maxX, minY, maxY, minZ, maxZ of children 0..7
  uint child[8];
} WideNode;

// Triangle in BVH order, laid out for Moller-Trumbore: v0, e1 = v1 - v0, e2 = v2 - v0.
// v0.w holds the material index, e1.w the triangle's canonical slot (the first slot of the array
// holding the same input triangle: spatial splits reference a triangle from several leaves, each
// through its own copy; closest hit returns the canonical slot) and e2.w its attribute flags
// (MCL_ATTR_*; all three as_float bits, never used in arithmetic).
typedef struct MCL_ALIGN16 {
  float4 v0;
  float4 e1;
  float4 e2;
} Triangle;

// Attribute flags in Triangle::e2.w (the bits of SceneTriangle::attributes). A triangle without a
// flag never reads its TriangleShading entry, so a scene where no triangle has attributes binds a
// 1-entry dummy buffer. The remaining bits are free for later per-triangle flags.
#define MCL_ATTR_NORMALS 1u
#define MCL_ATTR_UV 2u

// Per-triangle surface attributes, indexed like the BVH-ordered Triangle array (shading[h.tri]).
// Corner k (k = 0, 1, 2 at barycentrics (1 - u - v, u, v)) has the unit shading normal nk.xyz
// (MCL_ATTR_NORMALS; otherwise 0) and texture coordinates (nk.w, tv[k]) (MCL_ATTR_UV; otherwise 0;
// OBJ's convention, v = 0 at the image's bottom row). Read through shared/shading.h.
typedef struct MCL_ALIGN16 {
  float4 n0;  // xyz: normal at v0; w: u of v0
  float4 n1;  // xyz: normal at v1; w: u of v1
  float4 n2;  // xyz: normal at v2; w: u of v2
  float4 tv;  // x, y, z: v of v0, v1, v2; w: a textured emitter's mean emission luminance over the
              // triangle (its light-selection weight per area, host emitters.cpp), else 0
} TriangleShading;

#define MCL_NO_TEXTURE 0xffffffffu
typedef struct MCL_ALIGN16 {
  float4 albedo;    // rgb: Kd; w: albedo texture index (as_float bits), MCL_NO_TEXTURE for none
  float4 emission;  // rgb: Ke; w: 1 when both faces emit ("two_sided_emission"), else 0 (front only)
  float4 specular;  // rgb: Ks (glossy lobe); w: GGX roughness alpha (unused while Ks is 0)
  float4 alpha;     // x: alpha texture index (as_float bits, MCL_NO_TEXTURE: opaque); y: sign bit
                    // clear: a cut-out's cutoff (>= 0); set: stochastic transparency (glTF BLEND),
                    // -y the alpha factor (surface_texture.h alpha_hit_exists);
                    // z: channel of that texture holding alpha (as_float bits); w: the material kind
                    // MCL_MATERIAL_<kind> (as_float bits; shared/material_kinds.h; 0: diffuse)
  float4 params0;   // the kind's own parameters (bsdf_<kind>.h <kind>_from_material; 0 for diffuse)
  float4 params1;
  float4 maps;      // x: emission texture index (as_float bits, MCL_NO_TEXTURE: Ke alone; Le = Ke x its
                    // colour, surface_texture.h material_emission); y: metallic-roughness texture
                    // index (B metallic, G roughness, times the factors; MCL_NO_TEXTURE: none); z: normal
                    // map index + 1 (as_float bits; 0: none, so a zeroed Material has none; decoded
                    // tangent-space vectors, normal_map.h); w: bump map index + 1 (as_float bits; 0:
                    // none; the scaled height gradient per unit of UV, bump_map.h)
} Material;
// Floats per Material: the stride of the packet stages' gathers of material fields.
#define MCL_MATERIAL_FLOATS 28

// A ray: origin.w unused (0), dir.w = tmax.
typedef struct MCL_ALIGN16 {
  float4 origin;
  float4 dir;
} Ray;

// Closest hit: tri == MCL_NO_HIT on a miss; (u, v) barycentrics of v1 and v2.
typedef struct MCL_ALIGN16 {
  float t;
  uint tri;
  float u, v;
} Hit;

// An occlusion query: if nothing blocks the ray before ray.dir.w, (r, g, b) is written to
// shadowContrib[slot] (slots are per wave item, so the result does not depend on queue order).
typedef struct MCL_ALIGN16 {
  Ray ray;
  float r, g, b;
  uint slot;
} ShadowWork;

// Constants of one render, read by every stage.
typedef struct MCL_ALIGN16 {
  float4 camOrigin;   // camera position: the pinhole, or the centre of the thin lens
  float4 camTopLeft;  // direction (unnormalised) through the top-left corner of pixel (0, 0)
  float4 camDx;       // step of one pixel to the right
  float4 camDy;       // step of one pixel down
  float4 background;  // radiance of camera rays that hit nothing
  uint width, height, seed;
  float offsetScale;  // scene size for ray-origin offsets (offset_ray_origin): min(1, 2^k >= max |coord|)
  uint aoSampling;
  float aoDistance;
  uint shadowSlots;   // shadow contributions per sample (AO: 1; direct: lightSamples + 1)
  uint activeCount;   // entries of the active-pixel list the waves walk (all pixels unless adaptive)
  uint emitterCount;    // entries of the emitter table
  uint lightSamples;    // light samples per shading point (direct, and every path vertex's NEE)
  uint directSampling;  // MCL_DIRECT_LIGHT | MCL_DIRECT_BRDF | MCL_DIRECT_MIS
  float emitterPower;   // sum over emitters of area * luminance(Le): the light-selection normaliser
  int maxDepth;         // path integrator (Mitsuba's convention): -1 unlimited, 1 emitters seen, 2 direct
  uint rrDepth;         // path integrator: Russian roulette from this depth on
  float lensRadius;     // thin lens: aperture radius, 0 = pinhole
  float focusDistance;  // thin lens: distance of the plane in focus along the view direction
  float4 environment;   // rgb: constant environment radiance (times the map when there is one);
                        // w: 1 when an environment lights the scene, else 0
  uint envWidth, envHeight;  // environment map size, 0 x 0 for a constant environment
  float envRotateY;          // environment rotation about +y, radians
  uint textureCount;         // entries of the texture table
  // Light selection (kernels/stages/direct_light.h): each light kind's share of next-event samples,
  // proportional to its power (host/render/light_table.cpp); a scene with one kind gives it 1.
  float shareEnvironment, shareArea, sharePoint, shareSpot;
  float shareDirectional, shareSun;
  uint lightCount;  // entries of the light-record table (point, spot, directional, sun; kind by kind)
  uint packetAllRays;  // 1: incoherent rays take the packet traversal too (a small BVH: host frame_params.h)
  uint pointFirst, pointCount, spotFirst, spotCount;  // each kind's range of light records
  uint directionalFirst, directionalCount, sunFirst, sunCount;
  uint sampler;              // MCL_SAMPLER_INDEPENDENT | MCL_SAMPLER_SOBOL
  uint emissionTextured;     // 1 when a material's emission is textured, or an emitter is stochastically
                             // transparent (the packet stages then run the emitters' Le scalar)
  uint sobolSplits;          // sobol: independently scrambled sub-sequences, sample s in s % this (>= 1)
  uint sampleBlockShift;     // wave item order: runs of 2^this consecutive items are one pixel's samples
                             // (kernels/stages/stage_common.h; set per round of samples)
  uint instanceCount;        // placements of the two-level BVH (traverse_instances.h); 0: one level
  uint recordAovs;           // 1: the fused wave stages record each item's first-hit AOVs (record_aov.h)
  uint filterKind;           // MCL_FILTER_*: how the camera stage draws a sample's offset within its pixel
  float filterRadius;        // the pixel filter's radius in pixels (box 0.5: the pixel itself)
  // MCL_FILTER_TABLE: the filter's one-dimensional distribution over [-radius, radius] in
  // MCL_FILTER_BINS equal bins, entry i its CDF at bin i's right edge (the last is 1): x and y are
  // drawn from it independently, the filters being products of one function of x and one of y.
  float filterCdf[MCL_FILTER_BINS];
  uint countLanes;  // 1 (--profile): the shading stages count their hits shaded in lanes and one by one
  uint alphaTested;  // 1: some triangle carries MCL_ATTR_ALPHA (the traversals then run the alpha test)
} FrameParams;

// One emitting triangle. It is picked with probability area * luminance(Le) / emitterPower;
// cdf is the running sum of those probabilities up to and including this entry. guide is entry k's
// row of the pick's guide table (lights.h emitter_guide_bucket; host/render/emitter_guide.cpp):
// the emitter picked by the smallest u of bucket k, so a pick searches only [guide[k], guide[k + 1]].
typedef struct MCL_ALIGN16 {
  uint tri;  // index into the BVH-ordered triangles: the canonical slot (Triangle::e1.w)
  float cdf;
  float area;
  uint guide;
} Emitter;

// One light of the scene file's "lights" list that is not a triangle (kinds point, spot, directional,
// sun; kernels/shared/light_<kind>.h). Records are grouped by kind (FrameParams <kind>First,
// <kind>Count); within its kind a record is picked with probability direction.w (its power over
// the kind's), position.w the running sum of those up to and including it.
typedef struct MCL_ALIGN16 {
  float4 position;   // xyz: position (point, spot); w: cdf within the kind
  float4 direction;  // xyz: unit direction the light travels (spot: its axis); w: pick probability within the kind
  float4 intensity;  // rgb: intensity W/sr (point, spot), irradiance W/m^2 (directional), radiance (sun)
  float4 cone;       // spot: x cos(cutoff), y cos(beam width), z cutoff (radians), w 1 / (cutoff - beam width)
                     // (0 when they are equal); sun: x cos(half angle), y solid angle of the disk
} LightRecord;

// Textures (kernels/shared/texture.h, host/texture/): every mip level of every texture is one
// block of RGBA half-float texels (linear: 8- and 16-bit images were sRGB-decoded before the
// pyramid was filtered) in one texel buffer, rows bottom to top (row 0 holds v in [0, 1/height)).
// TextureDesc t's kept levels are levels[firstLevel .. firstLevel + levelCount); level k of the
// table is mip level dropped + k of the image as loaded (width x height at mip level 0): the
// texture budget drops the finest levels first.
// A texture is one use of an image: the same levels read through its own UV transform and wrap
// modes (glTF KHR_texture_transform and sampler wrapS / wrapT) have a TextureDesc each; a texture
// without them has the identity rows and repeats (bit for bit the lookup of an untransformed one).
#define MCL_WRAP_REPEAT 0u
#define MCL_WRAP_CLAMP 1u   // CLAMP_TO_EDGE: the edge texels continue outwards
#define MCL_WRAP_MIRROR 2u  // MIRRORED_REPEAT: every other repeat is flipped
typedef struct MCL_ALIGN16 {
  uint firstLevel;  // into the level table
  uint levelCount;  // levels kept (>= 1)
  uint dropped;     // finest levels dropped by the texture budget
  float lodBias;    // log2 of the loaded level-0 size's geometric mean: lod = log2(footprint) + this
  float4 uvRow0;    // xyz: u' = x u + y v + z (montecl's UVs, v up); w: wrap mode of u' (as_float bits)
  float4 uvRow1;    // xyz: v' = x u + y v + z; w: wrap mode of v' (as_float bits)
} TextureDesc;

// A level's texels: RGBA half (8 bytes), or 4 bytes of 8-bit codes decoded through the 256-entry
// tables of half values at the start of the texel buffer (ushorts [0, 256) the sRGB decode, [256,
// 512) code / 255; alpha always the latter): a finest level whose every half value is one of these
// is stored so (host/texture/scene_textures.cpp) and reads back the same bits in half the memory.
#define MCL_TEXELS_HALF 0u
#define MCL_TEXELS_SRGB8 1u    // rgb through the sRGB table, alpha linear
#define MCL_TEXELS_LINEAR8 2u  // every channel linear
#define MCL_TEXEL_TABLES 512u  // ushorts of the two tables
typedef struct MCL_ALIGN16 {
  uint offset;  // first texel of this level in the texel buffer, in units of its texel size
  uint width, height;
  uint format;  // MCL_TEXELS_*
} TextureLevel;

// Attribute flag (Triangle::e2.w, SceneTriangle::attributes kAlphaTested): the triangle's material
// has an alpha texture, or is stochastically transparent with an alpha factor below 1, so a hit on
// it exists only where the alpha test passes (surface_texture.h alpha_hit_exists). Opaque
// triangles never pay for the test.
#define MCL_ATTR_ALPHA 4u
// Attribute flag (SceneTriangle::attributes kHasColor): the triangle has vertex colours (glTF
// COLOR_0), vertexColors[3 tri + k].xyz at corner k, multiplying the material's base colour
// (surface_texture.h hit_albedo). A scene without them binds a 1-entry dummy buffer.
#define MCL_ATTR_COLOR 8u
// Attribute flag (SceneTriangle::attributes kHasTangents): the triangle has the file's tangents
// (glTF TANGENT), tangents[3 tri + k] at corner k: xyz the unit tangent, w its handedness (+1 or
// -1), in the triangle's own space (world, or its instance's object space); normal maps build
// their frame from them (normal_map.h) instead of from the triangle's UVs. A scene without them
// binds a 1-entry dummy buffer.
#define MCL_ATTR_TANGENTS 16u

// One placement of a bottom-level BVH in a two-level scene (kernels/shared/traverse_instances.h):
// the rows of its 3x4 affine maps (p' = (row . (p, 1)) per coordinate), the wide node of its bottom
// level's root and that level's first triangle (leaf references and canonical slots of the bottom
// levels are already rebased into the shared node and triangle arrays).
typedef struct MCL_ALIGN16 {
  float4 worldToObject[3];
  float4 objectToWorld[3];
  uint root;     // wide node index of the bottom level's root
  uint triBase;  // first triangle of the bottom level
  uint mesh;     // which bottom level (unique mesh)
  uint id;       // the instance's input index
} Instance;
#define MCL_NO_INSTANCE 0xffffffffu  // no instance was hit

#ifndef MCL_OPENCL
#include <cstddef>
static_assert(sizeof(BvhNode) == 32, "BvhNode layout");
static_assert(offsetof(BvhNode, maxX) == 16, "BvhNode layout");
static_assert(sizeof(WideNode) == 224 && alignof(WideNode) == 32, "WideNode layout");
static_assert(offsetof(WideNode, child) == 192, "WideNode layout");
static_assert(sizeof(Triangle) == 48, "Triangle layout");
static_assert(sizeof(TriangleShading) == 64, "TriangleShading layout");
static_assert(offsetof(TriangleShading, tv) == 48, "TriangleShading layout");
static_assert(sizeof(Material) == 112 && sizeof(Material) == 4 * MCL_MATERIAL_FLOATS, "Material layout");
static_assert(offsetof(Material, params0) == 64, "Material layout");
static_assert(sizeof(Ray) == 32, "Ray layout");
static_assert(sizeof(Hit) == 16, "Hit layout");
static_assert(sizeof(ShadowWork) == 48, "ShadowWork layout");
static_assert(sizeof(FrameParams) == 288 + 4 * MCL_FILTER_BINS && offsetof(FrameParams, instanceCount) == 256, "FrameParams layout");
static_assert(offsetof(FrameParams, shareEnvironment) == 176, "FrameParams layout");
static_assert(offsetof(FrameParams, sampler) == 240, "FrameParams layout");
static_assert(sizeof(LightRecord) == 64, "LightRecord layout");
static_assert(sizeof(Emitter) == 16, "Emitter layout");
static_assert(sizeof(TextureDesc) == 48 && offsetof(TextureDesc, uvRow0) == 16, "TextureDesc layout");
static_assert(sizeof(TextureLevel) == 16, "TextureLevel layout");
static_assert(offsetof(FrameParams, width) == 80, "FrameParams layout");
static_assert(sizeof(Instance) == 112 && offsetof(Instance, root) == 96, "Instance layout");
#endif
