// What a light-transport render is asked to do, shared by both engines.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "wavetrace/shading/mis.h"

namespace wavetrace {

// The five estimators of the rendering equation (see docs/sampling.md for what each counts).
enum class Strategy {
    Bsdf,     // follow BSDF samples; count emission wherever a path hits a light
    Light,    // continue along light-sampled directions, with a defensive uniform component
    Mixture,  // one-sample mixture: half BSDF, half light sampling, density 0.5 p_b + 0.5 p_l
    Nee,      // next-event estimation: shadow ray per vertex; BSDF-hit emission only after delta
    Mis,      // NEE and BSDF-hit emission both, weighted by the balance or power heuristic
};

const char* to_string(Strategy s);
std::optional<Strategy> parse_strategy(const std::string& name);

struct RenderConfig {
    int width = 0;
    int height = 0;
    int spp = 1;
    uint64_t seed = 0;
    Strategy strategy = Strategy::Mis;
    MisHeuristic heuristic = MisHeuristic::Power;
    int max_depth = 50;  // the most ray segments a path may have (the seed's max_depth)
    int rr_depth = 3;    // Russian roulette from this many scattering vertices on
    // The samples rendered are [first_sample, first_sample + spp) of each pixel's sequence:
    // rendering [0, k) and then [k, n) into one film gives the film of [0, n), bit for bit.
    int first_sample = 0;
    // Both engines render in passes of one or more samples of every pixel (the first pass
    // one sample, the later ones about pass_seconds long) and call this before each pass, on
    // the caller's thread, with the samples per pixel completed so far: no sample is being
    // added then, so the film may be read (a checkpoint). Returning true stops the render
    // there, so that every pixel holds the same number of samples (RenderStats::spp_done).
    // For interrupts, time limits and checkpoints.
    std::function<bool(int samples_done)> stop;
    // The length passes aim at when there is a stop function: long enough that the threads
    // seldom wait on each other and a tile keeps its samples together, short enough to stop
    // (or checkpoint) promptly.
    double pass_seconds = 0.5;
};

}  // namespace wavetrace
