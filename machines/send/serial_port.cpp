// termios serial port: O_NOCTTY raw mode, 8N1 without flow control, flock + TIOCEXCL for
// exclusive use, poll() for timeouts.
#include "machines/send/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <map>

#include "slicer/input_error.h"

namespace strand::machines {

namespace {

// Longer replies are cut into pieces of this size (no firmware sends such lines).
constexpr std::size_t kMaxLineBytes = 64 * 1024;

const std::map<int, speed_t>& bauds() {
  static const std::map<int, speed_t> kBauds = {
      {9600, B9600},     {19200, B19200},   {38400, B38400},   {57600, B57600},
      {115200, B115200}, {230400, B230400}, {460800, B460800},
      {500000, B500000}, {921600, B921600}, {1000000, B1000000}};
  return kBauds;
}

}  // namespace

bool supported_baud(int baud) { return bauds().count(baud) > 0; }

SerialPort::SerialPort(const std::string& path, int baud) : path_(path) {
  if (!supported_baud(baud)) {
    throw InputError("send.baud = " + std::to_string(baud) + ": must be one of 9600, 19200, 38400, 57600, 115200, 230400, 460800, 500000, 921600, 1000000");
  }
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    const int e = errno;
    throw InputError("send.port = " + path + ": " + (e == ENOENT ? "no such device" : e == EBUSY ? "busy (another program has it open)" : std::strerror(e)));
  }
  termios t{};
  if (!isatty(fd_) || tcgetattr(fd_, &t) != 0) {
    ::close(fd_);
    throw InputError("send.port = " + path + ": not a serial port");
  }
  if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    throw InputError("send.port = " + path + ": busy (another program has it open)");
  }
  ioctl(fd_, TIOCEXCL);  // later opens by others fail with EBUSY
  cfmakeraw(&t);
  t.c_cflag |= CLOCAL | CREAD;
  t.c_cflag &= ~(CSTOPB | CRTSCTS | PARENB);
  t.c_iflag &= ~(IXON | IXOFF | IXANY);
  cfsetispeed(&t, bauds().at(baud));
  cfsetospeed(&t, bauds().at(baud));
  tcsetattr(fd_, TCSANOW, &t);
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

void SerialPort::write_all(std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n > 0) {
      bytes.remove_prefix(static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
      pollfd p{fd_, POLLOUT, 0};
      if (::poll(&p, 1, 1000) < 0 && errno != EINTR) throw Disconnected(path_ + ": " + std::strerror(errno));
      if (p.revents & (POLLHUP | POLLERR)) throw Disconnected(path_ + ": the device went away");
      continue;
    }
    throw Disconnected(path_ + ": " + std::strerror(errno));
  }
}

std::optional<std::string> SerialPort::read_line(int timeout_ms) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    const auto end = pending_.find_first_of("\r\n");
    if (end != std::string::npos) {
      std::string line = pending_.substr(0, end);
      const std::size_t skip = (pending_[end] == '\r' && end + 1 < pending_.size() && pending_[end + 1] == '\n') ? 2 : 1;
      pending_.erase(0, end + skip);
      if (line.empty()) continue;  // the \n of a \r\n split across reads
      return line;
    }
    if (pending_.size() > kMaxLineBytes) {  // a device that never ends its lines
      std::string line = std::move(pending_);
      pending_.clear();
      return line;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return std::nullopt;
    pollfd p{fd_, POLLIN, 0};
    const int r = ::poll(&p, 1, static_cast<int>(left));
    if (r < 0 && errno == EINTR) return std::nullopt;  // a signal (Ctrl-C): let the caller look
    if (r < 0) throw Disconnected(path_ + ": " + std::strerror(errno));
    if (r == 0) return std::nullopt;
    char buf[512];
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n > 0) {
      pending_.append(buf, static_cast<std::size_t>(n));
    } else if (n == 0 || (errno != EAGAIN && errno != EINTR) || (p.revents & (POLLHUP | POLLERR))) {
      throw Disconnected(path_ + ": the device went away");
    }
  }
}

}  // namespace strand::machines
