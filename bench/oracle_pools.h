#pragma once
// What bench/adaptive_oracle and bench/adaptive_cost_oracle do with their pools of independent
// renders (docs/bench/adaptive-oracle-2026-12-07.md, "The measurement"): `means` holds K
// renders of a w x h image, render-major, RGB per pixel, each pixel of each render the mean
// of one step of `spp` samples; an allocation gives pixel p the mean of its first steps[p]
// renders from a pool's first one.
#include <cstdint>
#include <utility>
#include <vector>

#include "film/film.h"
#include "render/noise_estimate.h"

namespace tray {

/// Each pixel's relative variance of one sample, summed over R, G, B, from renders `first` to
/// `last` (exclusive) of `means` (render-major, RGB per pixel, each a mean of `spp` samples).
std::vector<double> relativeVariance(const std::vector<float>& means, size_t pixels, int first,
                                     int last, int spp, const Film& ref);

/// The image whose pixel p is the mean of renders first .. first + steps[p] - 1 of `means`.
Film imageOf(const std::vector<float>& means, const std::vector<int>& steps, int first, int w,
             int h);

/// The mean of `a` over each pixel's (2 radius + 1)^2 neighbourhood inside the image, the
/// pixel itself left out when `self` is false (what a rule deciding from its neighbours sees).
std::vector<double> boxAverage(const std::vector<double>& a, int w, int h, int radius, bool self);

/// TRay's own block decisions (render/noise_estimate.h: its steps, error estimate and
/// decideBlock over 8x8 blocks) replayed on `available` renders from `first`, one render
/// counting as one sample: each pixel's number of renders when every block has stopped.
std::vector<int> replay(const std::vector<float>& means, int first, int available, int w, int h,
                        SamplingPasses passes);

/// Uniform sampling's error at `x` (log-log between the points of `uniform`: pairs of
/// x (spp, or a cost) and error, x increasing).
double uniformAt(const std::vector<std::pair<double, double>>& uniform, double x);

}  // namespace tray
