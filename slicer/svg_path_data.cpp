// SVG path data ("M 10 10 l 5 0 a ...") read into sub-paths, and elliptical arcs converted
// from SVG's endpoint form to centre form.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "slicer/input_error.h"
#include "slicer/svg_scanner.h"
#include "slicer/svg_syntax.h"
#include "slicer/units.h"

namespace strand::slicer {

namespace {

int arg_count(char upper) {
  switch (upper) {
    case 'M':
    case 'L':
    case 'T':
      return 2;
    case 'H':
    case 'V':
      return 1;
    case 'C':
      return 6;
    case 'S':
    case 'Q':
      return 4;
    case 'A':
      return 7;
    default:
      return 0;
  }
}

// State of the path interpreter: current point, sub-path start, last control points.
struct PathBuilder {
  std::vector<SubPath> out;
  std::size_t max_pieces = 0;
  std::size_t pieces = 0;  // pieces and sub-paths stored so far

  void count() {
    if (++pieces > max_pieces) {
      throw InputError("path data has more than " + std::to_string(max_pieces) + " curve pieces");
    }
  }
  Vec2 cur = Vec2::Zero();
  Vec2 last_cubic_ctrl = Vec2::Zero();
  Vec2 last_quad_ctrl = Vec2::Zero();
  char prev = ' ';

  SubPath& current() {
    if (out.empty() || out.back().closed) {
      const Vec2 start = out.empty() ? Vec2::Zero() : out.back().start;
      count();
      out.push_back({start, {}, false});
    }
    return out.back();
  }
  void move_to(const Vec2& p) {
    if (!out.empty() && out.back().pieces.empty()) out.pop_back();
    count();
    out.push_back({p, {}, false});
    cur = p;
  }
  void line_to(const Vec2& p) {
    CurvePiece c;
    c.p[0] = p;
    add(c);
    cur = p;
  }
  void add(const CurvePiece& c) {
    SubPath& s = current();
    count();
    s.pieces.push_back(c);
  }
  void cubic_to(const Vec2& c1, const Vec2& c2, const Vec2& p) {
    CurvePiece c;
    c.kind = CurveKind::Cubic;
    c.p[0] = c1;
    c.p[1] = c2;
    c.p[2] = p;
    add(c);
    last_cubic_ctrl = c2;
    cur = p;
  }
  void quad_to(const Vec2& q, const Vec2& p) {
    const Vec2 from = cur;
    cubic_to(from + 2.0 / 3.0 * (q - from), p + 2.0 / 3.0 * (q - p), p);
    last_quad_ctrl = q;
  }
  void close() {
    SubPath& s = current();
    if ((cur - s.start).norm() > 0.0) line_to(s.start);
    s.closed = true;
    cur = s.start;
  }

  void apply(char cmd, const double* a) {
    const bool rel = std::islower(static_cast<unsigned char>(cmd));
    const char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
    const Vec2 base = rel ? cur : Vec2::Zero();
    const auto pt = [&](int i) -> Vec2 { return Vec2(a[i], a[i + 1]) + base; };
    const bool prev_cubic = prev == 'C' || prev == 'S';
    const bool prev_quad = prev == 'Q' || prev == 'T';
    switch (up) {
      case 'M':
        move_to(pt(0));
        break;
      case 'L':
        line_to(pt(0));
        break;
      case 'H':
        line_to(Vec2(a[0] + (rel ? cur.x() : 0.0), cur.y()));
        break;
      case 'V':
        line_to(Vec2(cur.x(), a[0] + (rel ? cur.y() : 0.0)));
        break;
      case 'C':
        cubic_to(pt(0), pt(2), pt(4));
        break;
      case 'S':
        cubic_to(prev_cubic ? 2 * cur - last_cubic_ctrl : cur, pt(0), pt(2));
        break;
      case 'Q':
        quad_to(pt(0), pt(2));
        break;
      case 'T':
        quad_to(prev_quad ? 2 * cur - last_quad_ctrl : cur, pt(0));
        break;
      case 'A': {
        const Vec2 to = pt(5);
        if ((to - cur).norm() == 0.0) break;  // SVG: an arc to the current point is omitted
        add(arc_piece(cur, a[0], a[1], a[2], a[3] != 0, a[4] != 0, to));
        cur = to;
        break;
      }
      default:
        break;
    }
    prev = up;
  }
};

bool read_args(SvgScanner& sc, char up, double* a) {
  const int n = arg_count(up);
  for (int i = 0; i < n; ++i) {
    if (up == 'A' && (i == 3 || i == 4)) {
      const auto f = sc.flag();
      if (!f) return false;
      a[i] = *f ? 1.0 : 0.0;
    } else {
      if (i > 0) sc.skip_comma_space();
      const auto v = sc.number();
      if (!v) return false;
      a[i] = *v;
    }
  }
  return true;
}

}  // namespace

CurvePiece arc_piece(const Vec2& from, double rx, double ry, double phi_deg, bool large_arc,
                     bool sweep, const Vec2& to) {
  rx = std::abs(rx);
  ry = std::abs(ry);
  CurvePiece line;
  line.p[0] = to;
  if (rx == 0.0 || ry == 0.0) return line;
  // SVG 1.1 implementation notes F.6.5: endpoint to centre parameterisation.
  const double phi = deg_to_rad(phi_deg);
  const double c = std::cos(phi), s = std::sin(phi);
  const Vec2 h = (from - to) / 2.0;
  const Vec2 p1(c * h.x() + s * h.y(), -s * h.x() + c * h.y());
  const double lambda = p1.x() * p1.x() / (rx * rx) + p1.y() * p1.y() / (ry * ry);
  if (lambda > 1.0) {
    rx *= std::sqrt(lambda);
    ry *= std::sqrt(lambda);
  }
  const double num = rx * rx * ry * ry - rx * rx * p1.y() * p1.y() - ry * ry * p1.x() * p1.x();
  const double den = rx * rx * p1.y() * p1.y() + ry * ry * p1.x() * p1.x();
  double k = std::sqrt(std::max(0.0, num / den));
  if (large_arc == sweep) k = -k;
  const Vec2 cp(k * rx * p1.y() / ry, -k * ry * p1.x() / rx);
  const Vec2 mid = (from + to) / 2.0;
  CurvePiece arc;
  arc.kind = CurveKind::Arc;
  arc.center = Vec2(c * cp.x() - s * cp.y(), s * cp.x() + c * cp.y()) + mid;
  arc.axes << c * rx, -s * ry, s * rx, c * ry;
  const Vec2 u((p1.x() - cp.x()) / rx, (p1.y() - cp.y()) / ry);
  const Vec2 v((-p1.x() - cp.x()) / rx, (-p1.y() - cp.y()) / ry);
  arc.t0_rad = std::atan2(u.y(), u.x());
  double dt = std::atan2(v.y(), v.x()) - arc.t0_rad;
  if (sweep && dt < 0) dt += kTwoPi;
  if (!sweep && dt > 0) dt -= kTwoPi;
  arc.sweep_rad = dt;
  return arc;
}

std::vector<SubPath> parse_path_data(std::string_view d, std::string* error,
                                     std::size_t max_pieces) {
  SvgScanner sc(d);
  PathBuilder b;
  b.max_pieces = max_pieces;
  char cmd = '\0';
  double a[7];
  while (!sc.done()) {
    if (std::isalpha(static_cast<unsigned char>(sc.peek()))) {
      cmd = sc.take();
      const char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
      if (std::string_view("MLHVCSQTAZ").find(up) == std::string_view::npos ||
          (b.out.empty() && up != 'M')) {
        if (error)
          *error =
              "unexpected '" + std::string(1, cmd) + "' at offset " + std::to_string(sc.pos() - 1);
        break;
      }
      if (up == 'Z') {
        b.close();
        b.prev = 'Z';
        continue;
      }
    } else if (cmd == '\0' || cmd == 'Z' || cmd == 'z') {
      if (error) *error = "number without a command at offset " + std::to_string(sc.pos());
      break;
    }
    const char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
    if (!read_args(sc, up, a)) {
      if (error)
        *error =
            "bad arguments for '" + std::string(1, cmd) + "' at offset " + std::to_string(sc.pos());
      break;
    }
    b.apply(cmd, a);
    if (up == 'M') cmd = (cmd == 'm') ? 'l' : 'L';  // implicit repeats after a move are lines
    sc.skip_comma_space();
  }
  if (!b.out.empty() && b.out.back().pieces.empty()) b.out.pop_back();
  return b.out;
}

}  // namespace strand::slicer
