#include "wavetrace/shading/estimator.h"

namespace wavetrace {

const char* to_string(Strategy s) {
    switch (s) {
        case Strategy::Bsdf:
            return "bsdf";
        case Strategy::Light:
            return "light";
        case Strategy::Mixture:
            return "mixture";
        case Strategy::Nee:
            return "nee";
        case Strategy::Mis:
            return "mis";
    }
    return "?";
}

std::optional<Strategy> parse_strategy(const std::string& name) {
    for (Strategy s :
         {Strategy::Bsdf, Strategy::Light, Strategy::Mixture, Strategy::Nee, Strategy::Mis})
        if (name == to_string(s)) return s;
    return std::nullopt;
}

}  // namespace wavetrace
