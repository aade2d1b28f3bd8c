// A serial port opened raw with POSIX termios: exclusive (a second sender is refused as
// busy), lines read with a timeout, a vanished device reported as a disconnect.
// Why not libserialport: it looks ports up in sysfs and refuses pseudo-terminals, so the
// simulated firmware of the test suite (openpty) could not be reached through it.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace strand::machines {

// The port went away (USB unplugged, controller reset the link) mid-job.
class Disconnected : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Baud rates termios offers by name.
bool supported_baud(int baud);

class SerialPort {
 public:
  // Throws InputError: no such device, not a terminal, busy (another program holds it),
  // permission denied, or an unsupported baud rate.
  SerialPort(const std::string& path, int baud);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  // Throws Disconnected.
  void write_all(std::string_view bytes);
  // One line without its end (\n, \r\n or \r), or nullopt after timeout_ms of silence.
  // Throws Disconnected.
  std::optional<std::string> read_line(int timeout_ms);

 private:
  int fd_ = -1;
  std::string path_;
  std::string pending_;  // bytes read past the last line end
};

}  // namespace strand::machines
