// `strand check` on a 1,000,000-move file: 100 layers of a dense serpentine (200 rows of
// 49 G1 pieces, G2/G3 U-turns), alternating direction like a log-pile.
// Target (issue 3): a few seconds for the whole check, parse included.
#include <benchmark/benchmark.h>

#include <charconv>
#include <string>

#include "machines/profile.h"
#include "postprocess/inspect/check.h"
#include "postprocess/inspect/crossings.h"

namespace {

constexpr int kLayers = 100;
constexpr int kRows = 200;         // per layer
constexpr int kPiecesPerRow = 49;  // G1 moves per row; + 1 arc = 50 moves per row
constexpr double kRowPitchMm = 0.4;
constexpr double kRowLengthMm = 78.0;

void put(std::string& out, double v) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 3);
  out.append(buf, r.ptr);
}

// One move: "G1 X.. Y..", with axes swapped on odd layers (rows along y).
void move(std::string& out, const char* g, double u, double v, bool swap) {
  out += g;
  out += " X";
  put(out, swap ? v : u);
  out += " Y";
  put(out, swap ? u : v);
}

std::string million_move_gcode() {
  std::string out;
  out.reserve(30'000'000);
  const double x0 = -kRowLengthMm / 2, y0 = -kRows * kRowPitchMm / 2;
  for (int l = 0; l < kLayers; ++l) {
    const bool swap = l % 2 == 1;
    const double z = 0.4 * (l + 1);
    out += ";LAYER_CHANGE\n;Z:" + std::to_string(z) + "\n;LAYER:" + std::to_string(l) + "\nG0 Z" +
           std::to_string(z) + "\n";
    move(out, "G0", x0, y0, swap);
    out += "\n";
    for (int r = 0; r < kRows; ++r) {
      const bool forward = r % 2 == 0;
      const double y = y0 + r * kRowPitchMm;
      for (int k = 1; k <= kPiecesPerRow; ++k) {
        const double t = static_cast<double>(k) / kPiecesPerRow;
        move(out, "G1", forward ? x0 + t * kRowLengthMm : x0 + (1 - t) * kRowLengthMm, y, swap);
        out += "\n";
      }
      const double end_x = forward ? x0 + kRowLengthMm : x0;
      // U-turn: half circle of radius pitch/2 to the next row; direction keeps the turn outside.
      const bool ccw = forward != swap;
      move(out, ccw ? "G3" : "G2", end_x, y + kRowPitchMm, swap);
      out += swap ? " I" : " J";
      put(out, kRowPitchMm / 2);
      out += swap ? " J0\n" : " I0\n";
    }
  }
  return out;
}

const std::string& text() {
  static const std::string t = million_move_gcode();
  return t;
}

void BM_CheckMillionMoves(benchmark::State& state) {
  using namespace strand;
  const auto machine = machines::load_profile("deltawasp-2040-clay");  // bounds + arc rule
  post::CheckOptions o;
  o.machine = &machine;
  std::size_t moves = 0;
  for (auto _ : state) {
    const auto r = post::check_gcode(text(), o);
    moves = r.moves;
    state.counters["crossings"] = static_cast<double>(r.crossing_count());
    state.counters["touches"] = static_cast<double>(r.touch_count());
    benchmark::DoNotOptimize(r.layers.data());
  }
  state.counters["moves"] = static_cast<double>(moves);
  state.counters["moves_per_s"] =
      benchmark::Counter(static_cast<double>(moves), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_CheckMillionMoves)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_ParseMillionMoves(benchmark::State& state) {
  for (auto _ : state) {
    const auto p = strand::post::parse_gcode(text());
    benchmark::DoNotOptimize(p.program.moves.data());
  }
  state.counters["lines_per_s"] =
      benchmark::Counter(1e6, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ParseMillionMoves)->Unit(benchmark::kMillisecond)->Iterations(3);

// Pathological layer for the grid: 2,000 dense nodes (3 concentric full circles each,
// ~100k chords crowding their cells) and 1,000 parallel diagonals 141 mm long, 0.14 mm
// apart, each crossing ~700 cells and many nodes (~19k real crossings). Target: well
// under a second.
strand::slicer::MotionProgram dense_nodes_and_long_lines() {
  using namespace strand::slicer;
  MotionProgram p;
  p.layers.push_back({0.5, 0.5});
  auto add = [&p](MoveKind kind, double x, double y) {
    Move mv;
    mv.kind = kind;
    mv.end_mm = {x, y, 0.5};
    mv.layer = 0;
    p.moves.push_back(mv);
    return &p.moves.back();
  };
  for (int i = 0; i < 2000; ++i) {
    const Vec2 c(-45.0 + 2.0 * (i % 45), 2.0 * (i / 45) - 45);
    for (double r : {0.3, 0.5, 0.7}) {
      add(MoveKind::Travel, c.x() + r, c.y());
      Move* arc = add(MoveKind::Deposit, c.x() + r, c.y());
      arc->is_arc = true;
      arc->center_mm = c;
    }
  }
  for (int i = 0; i < 1000; ++i) {
    const double o = 0.1 * i - 50;
    add(MoveKind::Travel, -50 + o, -50 - o + 100.05);
    add(MoveKind::Deposit, 50 + o, 50 - o + 100.05);
  }
  return p;
}

void BM_ContactsDenseNodesAndLongLines(benchmark::State& state) {
  const auto p = dense_nodes_and_long_lines();
  for (auto _ : state) {
    const auto r = strand::post::find_contacts(p, 0.01, 1e-3);
    benchmark::DoNotOptimize(r.crossings.data());
    state.counters["crossings"] = static_cast<double>(r.crossings.size());
  }
  state.counters["segments_moves"] = static_cast<double>(p.moves.size());
}
BENCHMARK(BM_ContactsDenseNodesAndLongLines)->Unit(benchmark::kMillisecond);

}  // namespace
