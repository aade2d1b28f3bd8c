// Fuzz target: any bytes as a file for `strand send` (line ends LF, CRLF, CR; framing;
// M110; characters refused) up to the first NUL, the commands streamed to Marlin, Klipper
// and GRBL with the lines after the NUL as the firmware's replies (then "ok"s), and the
// resume preamble at the file's middle line.
// Aborts when a write could confuse a controller: a CR, LF or '*' inside a command, a
// file M110 on the wire, a line number out of range, more than GRBL's buffer in flight.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "machines/send/resume.h"
#include "machines/send/streamer.h"
#include "slicer/input_error.h"

namespace {

using namespace strand;
using namespace strand::machines;

void require(bool ok) {
  if (!ok) std::abort();
}

bool clean(std::string_view c) {
  for (char ch : c) {
    const auto u = static_cast<unsigned char>(ch);
    if (ch == '\r' || ch == '\n' || ch == '*' || (u < 0x20 && ch != '\t') || u == 0x7f)
      return false;
  }
  return !c.empty();
}

// One write of a numbered-protocol streamer: M110 N0, an M105 probe or "N<k> cmd*<sum>".
void check_numbered(const std::string& w, std::size_t total) {
  if (w.empty() || w == "M110 N0\n" || w == "M105\n") return;
  require(w.back() == '\n' && w.find('\n') == w.size() - 1 && w[0] == 'N');
  const auto star = w.rfind('*');
  require(star != std::string::npos);
  const long n = std::strtol(w.c_str() + 1, nullptr, 10);
  require(n >= 1 && static_cast<std::size_t>(n) <= total);
  const std::string body = w.substr(w.find(' ') + 1, star - w.find(' ') - 1);
  require(clean(body) && !sets_line_number(body));
  require(numbered(n, body) + "\n" == w);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::string_view text = input.substr(0, input.find('\0'));
  const std::string_view answers =
      text.size() < input.size() ? input.substr(text.size() + 1) : std::string_view{};
  std::vector<Command> commands;
  try {
    commands = commands_of(text, "fuzz.gcode");
  } catch (const InputError&) {
    return 0;
  }
  for (const auto& c : commands) require(clean(c.text) && c.file_line >= 1);
  bool grbl_ok = true;
  try {
    refuse_grbl_realtime_characters(commands, "fuzz.gcode");
  } catch (const InputError&) {
    grbl_ok = false;
  }
  // the firmware's replies: the lines after the NUL (any junk), then "ok" for ever
  std::vector<std::string> replies;
  for (std::size_t at = 0; at < answers.size() && replies.size() < 2000;) {
    const auto end = answers.find_first_of("\r\n", at);
    replies.emplace_back(
        answers.substr(at, end == std::string_view::npos ? std::string_view::npos : end - at));
    at = end == std::string_view::npos ? answers.size() : end + 1;
  }
  for (Firmware fw : {Firmware::Marlin, Firmware::Klipper, Firmware::Grbl}) {
    if (fw == Firmware::Grbl && !grbl_ok) continue;
    Streamer s(fw, commands);
    std::size_t next = 0;
    for (int step = 0; step < 20000 && s.state() == StreamState::Running; ++step) {
      const std::string w = s.next_write();
      if (fw == Firmware::Grbl) {
        for (std::size_t at = 0; at < w.size();) {
          const auto end = w.find('\n', at);
          require(end != std::string::npos && clean(w.substr(at, end - at)));
          require(!sets_line_number(w.substr(at, end - at)));
          at = end + 1;
        }
      } else {
        check_numbered(w, s.total());
      }
      s.on_line(next < replies.size() ? replies[next++] : "ok");
      if (step % 7 == 6) {
        const std::string probe = s.on_silence();
        if (fw != Firmware::Grbl) check_numbered(probe, s.total());
      }
      require(s.acknowledged() <= s.total());
    }
  }
  static const MachineProfile valve = load_profile("bioprinter-xyz-reprap");
  static const MachineProfile plotter = load_profile("xy-plotter-servo");
  for (const MachineProfile* m : {&valve, &plotter}) {
    const ModalState st = modal_state_before(commands, commands[commands.size() / 2].file_line, *m);
    for (const auto& l : resume_preamble(*m, st))
      require(l.find_first_of("\r\n") == std::string::npos);
  }
  return 0;
}
