#pragma once
// tray-merge's work: parts of one render (regions, sample ranges, or both) into the image one
// machine would have rendered (docs/farm.md).
#include <string>
#include <vector>

#include "io/image_input.h"

namespace tray {

/// Combines the parts at `paths`: each pixel's filter-weighted sums are added over the parts
/// covering it (in sample order), then divided as the renderer does, so region parts paste bit
/// for bit and sample-range parts give the single-machine mean within float rounding. AOVs come
/// from the part holding sample 0, except `samples`, which is summed, and the layers averaged
/// over all samples (albedo, N, Z, light paths), which are the parts' means weighted by their
/// filter-weight (Z: hit-weight) sums. Throws tray::Error naming
/// the part and the problem: another job, an unfinished part, overlapping or missing samples.
ExrImage mergeParts(const std::vector<std::string>& paths);

/// Refuses (tray::Error, an input mistake) an output that is one of the parts, by name or as
/// the same file: merging would replace a part with the merged frame. Checked before reading.
void checkMergeOutput(const std::vector<std::string>& parts, const std::string& output);

}  // namespace tray
