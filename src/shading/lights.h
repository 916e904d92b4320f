// Light selection and sampling with solid-angle densities, for next-event estimation and
// MIS. Every emissive primitive is a light; so is every point light and a non-black background.
//
// Densities returned here include the probability of selecting the light, so they compare
// directly with BSDF densities in MIS weights. Next-event estimation selects a light by its
// importance at the vertex where the scene has few lights (lights/light_selection.h), else in
// proportion to power (area x pi x luminance of the radiance, doubled if two-sided; textured
// emitters count with luminance 1; a point light 4 pi x luminance of its intensity; the
// background as a sphere of the scene's radius, 4 pi^2 r^2 L).
//
// Point, spot and directional lights are deltas: a sample of one has "pdf" its selection
// probability and "radiance" intensity / d^2 (times a spot's falloff; a directional light's
// irradiance), flagged `delta`; no direction finds one. The one-sample strategies (light,
// mixture) sample directions from the other lights only (sample_direction_light,
// pdf_direction), in proportion to the same powers.
//
// An environment map is sampled in proportion to its texels' luminance times their solid angle,
// or, with MIS compensation (for MIS with BSDF sampling only, which then finds the rest), to
// max(L - mean L, 0) times it: Karlík et al., "MIS compensation: optimizing sampling techniques
// in multiple importance sampling" (2019), as pbrt-v4's image infinite light samples under MIS.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "lights/light_columns.h"
#include "lights/light_sample.h"
#include "lights/light_selection.h"
#include "sampling/distribution.h"
#include "scene/environment_view.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

struct Scene;

class LightSet {
  public:
    LightSet() = default;
    explicit LightSet(const Scene& scene, bool mis_compensation = false);

    bool empty() const { return count_ == 0; }
    // Whether any light can be found by a direction (an emitter or the background).
    bool has_area_lights() const { return count_ > delta_count_; }
    size_t size() const { return count_; }
    bool has_background() const { return background_; }
    // Probability that select() at (p, n) picks this emissive primitive (0 if it is not a
    // light), or the background; total: LightChoice::total of that select() if known, else 0.
    float selection_probability(PrimRef prim, Point3 p, Normal3 n, float total = 0.0f) const;
    float background_selection_probability(Point3 p, Normal3 n, float total = 0.0f) const;

    // Picks a light with selection number u_select for the vertex at p with geometric normal n
    // (zero in a medium; not empty()). Inline: both engines choose at every vertex.
    LightChoice select(float u_select, Point3 p, Normal3 n) const {
        return selection_.select(u_select, p, n);
    }
    // The choice itself, for the lights of many vertices at once (select_rows).
    const LightSelection& selection() const { return selection_; }
    // The chosen light's index among the planar emitters if it is a quad or a triangle of
    // constant radiance, else -1.
    int32_t planar_emitter_index(LightChoice choice) const {
        return choice.index < planar_of_.size() ? planar_of_[choice.index] : -1;
    }
    const PlanarEmitterColumns& planar_emitter_columns() const { return planar_columns_; }
    // The same for spheres of constant radiance.
    int32_t sphere_emitter_index(LightChoice choice) const {
        return choice.index < sphere_of_.size() ? sphere_of_[choice.index] : -1;
    }
    const SphereEmitterColumns& sphere_emitter_columns() const { return sphere_columns_; }
    // The same for point and directional lights.
    int32_t delta_light_index(LightChoice choice) const {
        const size_t i = choice.index - emitters_.size();
        return choice.index >= emitters_.size() && i < delta_of_.size() ? delta_of_[i] : -1;
    }
    const DeltaLightColumns& delta_light_columns() const { return delta_columns_; }
    // Whether the chosen light is an environment map (sampled by the lane formula
    // EnvironmentLightPoint, lights/light_sample-inl.h, from these two).
    bool is_environment(LightChoice choice) const {
        return has_environment() && choice.index == count_ - 1;
    }
    bool has_environment() const { return background_ && !environment_.empty(); }
    // Whether the environment map is sampled with MIS compensation (its weights the excess).
    bool environment_compensated() const { return environment_compensated_; }
    const EnvironmentView& environment_view() const { return environment_view_; }
    Distribution2DTables environment_tables() const { return environment_.tables(); }

    // Samples a point on the chosen light as seen from `ref` with two uniform numbers.
    LightSample sample(
        const Scene& scene, Point3 ref, LightChoice choice, float u1, float u2) const;
    // Picks a light other than a point light, in proportion to power, and samples a point on
    // it as seen from `ref` with three uniform numbers (has_area_lights()): the light-sampled
    // directions of the one-sample strategies, whose density is pdf_direction.
    LightSample sample_direction_light(
        const Scene& scene, Point3 ref, float u_select, float u1, float u2) const;
    // Density with which a light sample from `ref` (geometric normal ref_n, zero in a medium;
    // ref_total as selection_probability's), chosen by select(), produces direction wi hitting
    // emitter `prim` at distance dist. Zero for non-emitters.
    float pdf_prim(const Scene& scene,
                   Point3 ref,
                   Normal3 ref_n,
                   float ref_total,
                   PrimRef prim,
                   Vec3 wi,
                   float dist) const;
    // The same for background direction wi.
    float pdf_background(
        const Scene& scene, Point3 ref, Normal3 ref_n, float ref_total, Vec3 wi) const;
    // Total density of direction wi from `ref` over all lights, ignoring occlusion: the
    // density sample_direction_light assigns to wi. O(number of emitters).
    float pdf_direction(const Scene& scene, Point3 ref, Vec3 wi) const;

  private:
    float prim_pdf_given_selection(
        const Scene& scene, Point3 ref, PrimRef prim, Vec3 wi, float dist) const;
    float background_pdf_given_selection(const Scene& scene, Vec3 wi) const;

    std::vector<PrimRef> emitters_;  // light i < emitters_.size()
    std::vector<int32_t> planar_of_;   // light i: index into planar_columns_, or -1
    PlanarEmitterColumns planar_columns_;
    std::vector<int32_t> sphere_of_;  // light i: index into sphere_columns_, or -1
    SphereEmitterColumns sphere_columns_;
    std::vector<int32_t> delta_of_;  // Scene::lights[i]: index into delta_columns_, or -1
    DeltaLightColumns delta_columns_;
    std::unordered_map<uint32_t, uint32_t> index_;  // PrimRef bits -> light index
    bool background_ = false;                       // the last light, if present
    size_t count_ = 0;
    size_t delta_count_ = 0;  // Scene::lights: lights emitters_.size() .. + delta_count_
    // For the one-sample strategies, by power: without point lights 1 and selection_'s power;
    // with them, the share of the other lights' power, and the selection among those alone (the
    // background as entry emitters_.size()).
    float area_fraction_ = 1.0f;
    Distribution1D area_select_;
    LightSelection selection_;
    // Over the environment image's texels: luminance (or its excess over the mean, with MIS
    // compensation) times the texel's solid angle.
    Distribution2D environment_;
    bool environment_compensated_ = false;
    EnvironmentView environment_view_;
};

// Radiance a surface emits towards wo (unit, away from the surface, on the side the ray came
// from): 0 unless the material emits; one-sided emitters emit only on their front; under a
// metallic-roughness material's clearcoat, darkened by the coat's Fresnel at wo
// (coat_emission_weight), so that it depends on wo.
struct SurfaceHit;
Color emitted_radiance(const Scene& scene, const SurfaceHit& hit, Vec3 wo);

}  // namespace wavetrace
