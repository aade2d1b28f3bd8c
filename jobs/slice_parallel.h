// The slice job's layers on every core (oneTBB), in the calling task arena (the job limits its
// threads there): cut in parallel; thin features found in parallel; filled in parallel a
// bounded window of layers ahead of the writer, then ordered, planned and written one at a
// time in layer order. Nothing a layer's
// fill reads is shared and mutable, and everything summed is summed in layer order, so the
// bytes are those of one thread.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "patterns/region_fill.h"
#include "patterns/thin_feature.h"
#include "postprocess/plan/produce.h"
#include "slicer/mesh.h"
#include "slicer/mesh_slicer.h"
#include "slicer/region.h"

namespace strand::jobs {

// slicer::slice_layers with the layers cut in parallel: the same regions and stats.
std::vector<slicer::Region> cut_layers(const slicer::Mesh& mesh, double layer_height_mm,
                                       int layers, slicer::ContourStats* stats);

// patterns::print_thin_features with the layers' beads found in parallel: the same fill
// regions, beads and sums (added in layer order).
patterns::PartThinBeads thin_features_in_parallel(std::vector<slicer::Region>& layers,
                                                  double nozzle_mm, double layer_height_mm);

// Every layer of `source` filled (in parallel, at most two layers per thread in flight),
// then in layer order: made (PartFillSource::layer_from), shown to `on_layer`, and added to
// `producer`. A fill's InputError is thrown when its layer's turn comes, as one thread would.
// `complete(k, fill)`, if given, runs on each fill in the parallel stage (thread-safe, per
// layer only).
void produce_filled(patterns::PartFillSource& source, post::LayerProducer& producer,
                    const std::function<void(std::size_t, const slicer::Layer&)>& on_layer,
                    const std::function<void(std::size_t, patterns::LayerFill&)>& complete = {});

}  // namespace strand::jobs
