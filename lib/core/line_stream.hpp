#pragma once
// An ostream for one of several threads writing progress to one stream: it collects a line and
// writes it whole, under a lock the threads share, so lines from threads side by side never mix.
#include <mutex>
#include <ostream>
#include <streambuf>
#include <string>

namespace corofem {

class LineStream : public std::ostream {
 public:
  LineStream(std::ostream& target, std::mutex& lock);
  ~LineStream() override;  ///< writes an unfinished last line
  LineStream(const LineStream&) = delete;
  LineStream& operator=(const LineStream&) = delete;

 private:
  class Buffer : public std::streambuf {
   public:
    Buffer(std::ostream& target, std::mutex& lock) : target_(target), lock_(lock) {}
    void write_line();

   protected:
    int_type overflow(int_type c) override;
    std::streamsize xsputn(const char* s, std::streamsize n) override;

   private:
    std::ostream& target_;
    std::mutex& lock_;
    std::string line_;
  };
  Buffer buffer_;
};

}  // namespace corofem
