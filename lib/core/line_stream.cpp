#include "core/line_stream.hpp"

namespace corofem {

LineStream::LineStream(std::ostream& target, std::mutex& lock)
    : std::ostream(nullptr), buffer_(target, lock) {
  rdbuf(&buffer_);
}

LineStream::~LineStream() {
  buffer_.write_line();
}

void LineStream::Buffer::write_line() {
  if (line_.empty()) return;
  const std::lock_guard<std::mutex> hold(lock_);
  target_ << line_ << std::flush;
  line_.clear();
}

LineStream::Buffer::int_type LineStream::Buffer::overflow(int_type c) {
  if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
  line_ += traits_type::to_char_type(c);
  if (c == '\n') write_line();
  return c;
}

std::streamsize LineStream::Buffer::xsputn(const char* s, std::streamsize n) {
  for (std::streamsize i = 0; i < n; ++i) overflow(traits_type::to_int_type(s[i]));
  return n;
}

}  // namespace corofem
