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
    const float u = -std::expm1(-flight);  // the uniform the depth was drawn from
    const float thirds = std::min(3.0f * u, std::nextafter(3.0f, 0.0f));
    const int c = static_cast<int>(thirds);
    flight = sample_free_flight(1.0f, thirds - float(c));
    const float sigma = sigma_t[c];
    const float dist = sigma > 0.0f ? flight / sigma : kInfinity;
    if (dist < seg) {
        const Color density = sigma_t * medium_transmittance(sigma_t, dist);
        const float mixture = (density.x + density.y + density.z) / 3.0f;
        f.scatters = true;
        f.dist = dist;
        f.weight = mixture > 0.0f ? density / mixture : Color(0.0f);
        return f;
    }
    const Color tr = medium_transmittance(sigma_t, seg);
    const float mixture = (tr.x + tr.y + tr.z) / 3.0f;
    f.weight = mixture > 0.0f ? tr / mixture : Color(0.0f);
    if (sigma > 0.0f) flight -= sigma * seg;
    return f;
}

}  // namespace wavetrace
