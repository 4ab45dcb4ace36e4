// scene_textures.h: every texture a scene's materials name, loaded once each (image/image_read.h),
// sRGB-decoded (integer images), mip-mapped and packed into the device's texture
// tables (kernels/shared/types.h TextureDesc / TextureLevel, RGBA half texels, a finest level of 8-bit codes in 4 bytes) under a byte budget.
// Reads Scene::materials' textures (albedo, alpha, emission, metallic-roughness, normal, bump);
// writes SceneTextures.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/shared/types.h"
#include "scene/scene.h"

namespace montecl {

// The automatic texture budget (--texture-budget 0): at most this, and at most the device's
// largest allocation (the texels are one buffer).
constexpr std::uint64_t kDefaultTextureBudget = 1024ull << 20;

// A material's textures: indices into SceneTextures::textures (MCL_NO_TEXTURE: none) and the
// channel of the alpha texture holding alpha (3 when the file has an alpha channel, else 0).
struct MaterialTextures {
  std::uint32_t albedo = MCL_NO_TEXTURE;
  std::uint32_t alpha = MCL_NO_TEXTURE;
  std::uint32_t alphaChannel = 0;
  std::uint32_t emission = MCL_NO_TEXTURE;  // emission texture (colour, like the albedo's)
  std::uint32_t metallicRoughness = MCL_NO_TEXTURE;  // read linear (no sRGB decode)
  std::uint32_t transmission = MCL_NO_TEXTURE;       // glTF transmissionTexture, linear (R)
  std::uint32_t normal = MCL_NO_TEXTURE;  // decoded tangent-space vectors (normal_map.h)
  std::uint32_t bump = MCL_NO_TEXTURE;    // scaled height gradients (bump_gradient.h, bump_map.h)
};

struct SceneTextures {
  std::vector<TextureDesc> textures;
  std::vector<TextureLevel> levels;
  std::vector<std::uint16_t> texels;    // the code tables, then each level: RGBA half (4 a texel) or 8-bit codes (2)
  std::vector<std::string> files;       // textures[i] was read from files[i]
  std::vector<MaterialTextures> materials;  // one per Scene::materials entry
  std::uint64_t bytes() const { return texels.size() * sizeof(std::uint16_t); }
  bool anyAlpha() const;
};

// True when material m's bump map is used: it has one and no normal map (a normal map, the more
// specific relief, wins).
bool usesBumpMap(const MaterialDesc& m);

// True when a material of scene names a texture.
bool sceneHasTextures(const Scene& scene);

// Which textures an image reads, beside the cut-outs' alpha textures, which are always loaded (they
// change what every ray sees, AO's included). A texture no image reads is never decoded: AO reads
// none of these, the albedo AOV (and the denoiser's albedo guide) reads the reflectance, the normal
// AOV (and guide) the normal maps, the lit integrators all of them (render/integrators.h
// textureUsesOf).
struct TextureUses {
  bool reflectance = true;  // albedo and metallic-roughness textures (the BSDF's colour)
  bool emission = true;
  bool normal = true;       // normal maps and bump maps (the shading normal)
};

// Loads the textures of scene's materials. A file used both as colour and as an alpha texture
// without an alpha channel is loaded twice (sRGB-decoded, and linear for alpha); otherwise once.
// Over budget, the finest levels are dropped (one warning naming the textures). Throws InputError
// "<texture file>: material '<name>' <map_Kd|map_d>: cannot read image: <reason>".
// Leaves out the textures uses says no image reads (their materials get no texture index).
SceneTextures loadSceneTextures(const Scene& scene, std::uint64_t budgetBytes,
                                std::vector<std::string>& warnings, TextureUses uses = {});

// Whether material i is alpha-tested: it has an alpha texture in textures (may be null), or is
// stochastically transparent (alphaBlend) with an alpha factor below 1.
bool materialAlphaTested(const std::vector<MaterialDesc>& materials, const SceneTextures* textures, std::size_t i);
bool anyAlphaTested(const std::vector<MaterialDesc>& materials, const SceneTextures* textures);

// tris (BVH order) with MCL_ATTR_ALPHA set in e2.w on every triangle whose material is
// alpha-tested (materialAlphaTested; the traversals test only those); empty when none is.
std::vector<Triangle> alphaFlaggedTriangles(const std::vector<Triangle>& tris, const std::vector<MaterialDesc>& materials,
                                            const SceneTextures* textures);

// Writes the texture indices and alpha channel of textures.materials[i] into device material i
// (kernels/shared/types.h Material: albedo.w, alpha.x, alpha.z, maps.x, maps.y, maps.z, maps.w).
void setTextureIndices(std::vector<Material>& materials, const SceneTextures& textures);

// Packs already decoded level-0 images (files names them in messages) the same way: what
// loadSceneTextures does after reading; for tests.
struct RgbaImage;
void packTextures(SceneTextures& out, std::vector<RgbaImage> images, std::uint64_t budgetBytes,
                  std::vector<std::string>& warnings);

// One texel of a glTF specular-glossiness map (RGB the specular colour, decoded; A the glossiness)
// as a metallic-roughness texel (0, roughness, metallic, 1) for the factors (specular RGB,
// glossiness) and the material's diffuse colour (MaterialDesc::specGlossMap).
glm::vec4 specGlossTexel(glm::vec4 texel, glm::vec4 factors, glm::vec3 diffuse);

// Float -> half (round to nearest even) and back, as the device's vload_half reads it.
std::uint16_t floatToHalf(float f);
float halfToFloat(std::uint16_t h);

}  // namespace montecl
