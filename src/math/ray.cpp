#include "wavetrace/math/ray.h"

#include "math/lanes-inl.h"

namespace wavetrace {

float origin_offset(Point3 p) {
    namespace lanes = HWY_NAMESPACE;
    return lanes::OriginOffset<lanes::OneLane>(lanes::to_lanes(p));
}

}  // namespace wavetrace
