#include "media/free_flight.h"

#include <algorithm>

#include "math/lanes-inl.h"
#include "wavetrace/math/constants.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
using lanes::OneLane;

float sample_free_flight(float density, float u) {
    return lanes::OpticalDepth<OneLane>(u) / density;
}

ChromaticFlight chromatic_flight(Color sigma_t, float seg, float& flight) {
    ChromaticFlight f;
    const int c = draw_flight_channel(flight);
    const float sigma = sigma_t[c];
    const float dist = sigma > 0.0f ? flight / sigma : kInfinity;
    if (dist < seg) {
        f.scatters = true;
        f.dist = dist;
        f.weight = channel_mixture_weight(sigma_t * medium_transmittance(sigma_t, dist));
        return f;
    }
    f.weight = channel_mixture_weight(medium_transmittance(sigma_t, seg));
    if (sigma > 0.0f) flight -= sigma * seg;
    return f;
}

int draw_flight_channel(float& flight) {
    const float u = -std::expm1(-flight);  // the uniform the depth was drawn from
    const float thirds = std::min(3.0f * u, std::nextafter(3.0f, 0.0f));
    const int c = static_cast<int>(thirds);
    flight = sample_free_flight(1.0f, thirds - float(c));
    return c;
}

Color channel_mixture_weight(Color f) {
    const float mixture = (f.x + f.y + f.z) / 3.0f;
    return mixture > 0.0f ? f / mixture : Color(0.0f);
}

}  // namespace wavetrace
