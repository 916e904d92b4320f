// Free flights through homogeneous media: the transmittance of a segment, a sampled distance,
// and the channel-mixture flights of media whose extinction differs per channel. Scalar code,
// which both engines' resolve_segment runs; the grey flight's lane formula is
// medium_flight-inl.h.
#pragma once

#include <cmath>

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Beer-Lambert transmittance exp(-density * length) through one homogeneous medium. An
// unbounded segment (length infinity) in a medium that extinguishes anything absorbs
// everything; one of density 0 lets everything through (exp(-0 * inf) would be NaN), as the
// free-flight sampling does, which never scatters there.
inline float medium_transmittance(float density, float length) {
    if (!(density > 0.0f)) return 1.0f;
    return std::isinf(length) ? 0.0f : std::exp(-density * length);
}
// Per channel, for extinctions sigma_t (one exponential for a grey medium).
inline Color medium_transmittance(Color sigma_t, float length) {
    if (sigma_t.x == sigma_t.y && sigma_t.y == sigma_t.z)
        return Color(medium_transmittance(sigma_t.x, length));
    return {medium_transmittance(sigma_t.x, length), medium_transmittance(sigma_t.y, length),
            medium_transmittance(sigma_t.z, length)};
}

// Free-flight distance (world units) in a homogeneous medium of extinction `density`,
// sampled proportional to density * exp(-density * s): -ln(1 - u) / density.
float sample_free_flight(float density, float u);

// A free flight over a segment of world length seg (infinity: it hits nothing) in a medium
// whose channels' extinctions sigma_t differ. One channel, chosen uniformly, samples the
// distance; the weight divides by the mixture of the three channels' densities (spectral MIS,
// the one-sample model: Miller, Georgiev and Jarosz 2019, "A null-scattering path integral
// formulation of light transport", §6; Mitsuba 3's volpath), so that a channel that thins out
// does not starve the others:
//   scatters at t:   weight = sigma_t exp(-sigma_t t) / mean_c(sigma_c exp(-sigma_c t))
//   passes the seg:  weight = exp(-sigma_t seg) / mean_c(exp(-sigma_c seg))
// The channel and the distance both come from `flight`, the optical depth drawn for the
// segment: its uniform 1 - exp(-flight) splits into the channel (which third) and a fresh
// uniform for the depth, so each segment chooses anew, as the per-segment mixture needs (a
// channel kept over segments would bias the passes after the first); what a pass leaves is
// again an exponential depth, independent of the choice, and carries over.
struct ChromaticFlight {
    bool scatters = false;
    float dist = 0.0f;  // scatters: world distance from the segment's start
    Color weight{0.0f};
};
ChromaticFlight chromatic_flight(Color sigma_t, float seg, float& flight);

// The channel-mixture flights' two steps, which heterogeneous media share: the channel that
// samples this segment's distance, drawn from `flight` (replaced by the fresh depth), and the
// weight f / mean_c(f_c) of the channels' densities (scattering) or transmittances (passing).
int draw_flight_channel(float& flight);
Color channel_mixture_weight(Color f);

}  // namespace wavetrace
