// Cutting and filling layers in parallel (jobs/slice_parallel.h).
#include "jobs/slice_parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <exception>

namespace strand::jobs {

std::vector<slicer::Region> cut_layers(const slicer::Mesh& mesh, double layer_height_mm,
                                       int layers, slicer::ContourStats* stats) {
  const slicer::LayerCuts cuts(mesh, layer_height_mm, layers);
  const std::size_t n = static_cast<std::size_t>(cuts.layers());
  std::vector<slicer::Region> out(n);
  std::vector<slicer::ContourStats> per_layer(n);  // one each: no counter shared by threads
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      out[k] = cuts.cut(static_cast<int>(k), per_layer[k]);
    }
  });
  if (stats) {
    for (const slicer::ContourStats& s : per_layer) *stats += s;
  }
  return out;
}

patterns::PartThinBeads thin_features_in_parallel(std::vector<slicer::Region>& layers,
                                                  double nozzle_mm, double layer_height_mm) {
  patterns::PartThinBeads out;
  out.per_layer.resize(layers.size());
  std::vector<double> length_mm(layers.size(), 0.0);
  // Layer k's call reads and replaces layers[k] alone.
  tbb::parallel_for(std::size_t{0}, layers.size(), [&](std::size_t k) {
    patterns::ThinFeatures t = patterns::thin_features(layers[k], nozzle_mm, layer_height_mm);
    if (t.beads.empty()) return;
    layers[k] = std::move(t.fill_region);
    length_mm[k] = t.length_mm;
    out.per_layer[k] = std::move(t.beads);
  });
  for (std::size_t k = 0; k < layers.size(); ++k) {  // in layer order, as one thread sums
    out.count += static_cast<int>(out.per_layer[k].size());
    out.length_mm += length_mm[k];
  }
  return out;
}

namespace {

struct Filled {
  std::size_t k = 0;
  patterns::LayerFill fill;
  std::exception_ptr error;  // rethrown in layer order
};

}  // namespace

void produce_filled(patterns::PartFillSource& source, post::LayerProducer& producer,
                    const std::function<void(std::size_t, const slicer::Layer&)>& on_layer,
                    const std::function<void(std::size_t, patterns::LayerFill&)>& complete) {
  const std::size_t n = source.layer_count();
  // Layers in flight: enough to keep every thread busy while the writer catches up, few
  // enough that memory stays that of a handful of layers, whatever the part's height.
  const std::size_t in_flight = 2 * static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
  std::size_t next = 0;
  // The first error, in layer order: no more layers go in, and the ones in flight pass through
  // unwritten, so the pipeline ends normally (a filter that throws cancels it, and oneTBB then
  // leaves the items between filters undestroyed) and the error is thrown after it.
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  tbb::parallel_pipeline(
      in_flight,
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                          [&](tbb::flow_control& fc) -> std::size_t {
                                            if (next == n || failed.load()) {
                                              fc.stop();
                                              return 0;
                                            }
                                            return next++;
                                          }) &
          tbb::make_filter<std::size_t, Filled>(tbb::filter_mode::parallel,
                                                [&](std::size_t k) {
                                                  Filled f;
                                                  f.k = k;
                                                  if (failed.load()) return f;
                                                  try {
                                                    f.fill = source.fill(k);
                                                    if (complete) complete(k, f.fill);
                                                  } catch (...) {
                                                    f.error = std::current_exception();
                                                  }
                                                  return f;
                                                }) &
          tbb::make_filter<Filled, void>(tbb::filter_mode::serial_in_order, [&](Filled f) {
            if (error) return;
            try {
              if (f.error) std::rethrow_exception(f.error);
              const slicer::Layer layer = source.layer_from(f.k, std::move(f.fill));
              if (on_layer) on_layer(f.k, layer);
              producer.add(layer);
            } catch (...) {
              error = std::current_exception();
              failed.store(true);
            }
          }));
  if (error) std::rethrow_exception(error);
}

}  // namespace strand::jobs
