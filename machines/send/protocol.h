// The words of the host <-> firmware serial protocols: a G-code file as the commands to send
// (comments stripped, each with its file line), Marlin/RepRapFirmware line numbers and
// checksums, and what a reply line means for Marlin, RepRapFirmware and GRBL.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "machines/profile.h"

namespace strand::machines {

// One command to send and where it came from.
struct Command {
  int file_line = 0;  // 1-based line in the G-code file; 0 for commands Strand adds
  std::string text;   // without comments, trimmed
  bool operator==(const Command&) const = default;
};

// The commands of a G-code file in order (empty and comment-only lines skipped). Lines end
// at LF, CRLF or a lone CR alike (a CR-only file has as many lines as an LF one). A file's
// own serial framing ("N12 G1 X5*57") is removed: the sender numbers lines itself. Throws
// InputError naming `origin` and the line when the text is not G-code (binary data, lines
// that do not start with a command letter, a control character or a '*' inside a command,
// more than kMaxSendLines commands).
std::vector<Command> commands_of(std::string_view gcode, const std::string& origin);
inline constexpr std::size_t kMaxSendLines = 50'000'000;

// M110 (set line number): Strand owns the line numbering of the serial protocol, so the
// file's own M110 lines are not sent (one would make Marlin replay or skip lines; GRBL has no
// M110).
bool sets_line_number(std::string_view command);

// GRBL acts on '?', '!', '~' and bytes from 0x80 wherever they appear in the stream (status,
// feed hold, cycle start, overrides): a command holding one is refused (InputError naming
// `origin` and the line) before anything is sent.
void refuse_grbl_realtime_characters(const std::vector<Command>& commands,
                                     const std::string& origin);

// XOR of the bytes, as Marlin and RepRapFirmware check it.
int checksum(std::string_view text);
// "N12 G1 X5*57": the line number and checksum framing.
std::string numbered(long n, std::string_view command);

enum class ReplyKind {
  Ok,         // command accepted ("ok", "ok T:20.0 ...")
  Resend,     // "Resend: N" / "rs N": send again from line N
  Busy,       // "busy: processing" / "echo:busy: paused for user": the firmware is alive
  LineError,  // a transmission error (checksum, line number); a Resend follows
  Error,      // a firmware error that stops the job ("Error:Printer halted", GRBL "error:9",
              // Klipper "!! Move out of range")
  Alarm,      // GRBL "ALARM:n"; also stops the job
  Status,     // GRBL status report "<Idle|MPos:...>"
  Restart,    // the controller restarted ("start", "Grbl 1.1h ['$' for help]")
  Other,      // echo:, temperatures, anything else
};

struct Reply {
  ReplyKind kind = ReplyKind::Other;
  long line = 0;      // Resend: the line number asked for
  bool idle = false;  // Status: the machine is idle (everything sent has run)
  std::string text;   // the reply as received (trimmed)
};

Reply parse_reply(std::string_view line, Firmware firmware);

}  // namespace strand::machines
