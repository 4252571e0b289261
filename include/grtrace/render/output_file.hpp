// grtrace/render/output_file.hpp
// Output files written safely, whole or not at all, alone or as a set (POSIX; no third-party dependency).
// Every grtrace writer (write_exr, write_png_*, the tools' CSV/JSON/chart files, grtrace::viz's PNGs) goes
// through here.
//
//   grtrace::write_file_atomically("out.csv", [&](std::ostream& os) { os << ...; });   // one file
//
//   grtrace::OutputSet set;                               // several files of one run: all new or all old
//   grtrace::write_exr(set, "frame.exr", image);          // (exr_io.hpp / png_preview.hpp overloads)
//   grtrace::write_png_preview(set, "frame.png", image);
//   set.commit();                                         // renames every temporary into place
//
// Safety (why it is written this way):
// - The temporary is a sibling of the target (same directory, so rename() is atomic) named
//   "<target name>.tmp-<16 random characters from getrandom()>", created with
//   open(O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666): the name cannot be predicted, an existing
//   file or symbolic link of that name makes the creation fail (a new name is drawn) instead of being
//   followed, and the permissions are those of a normal file (0666 minus the umask). The data is written
//   through that descriptor only; the temporary is never reopened by name.
// - rename() replaces the final name itself: a symbolic link planted at the final name is replaced, never
//   followed, so the file it points to is left unchanged.
// - check_output_path() refuses, before anything is created: a missing or unwritable directory, a target that
//   is a directory, a device, a FIFO or a socket, an empty name or one longer than the directory allows, and
//   a target or directory whose inode flags forbid the rename (immutable or append-only, chattr +i / +a).
// - A set is committed by writing every temporary first and then renaming them one after the other with
//   the cleanup signals (below) blocked in the committing thread and deferred by the handler in any
//   other thread, so those signals see either the old set or the new one.
//   What POSIX does not allow us to close: SIGKILL, a crash or a power loss between two renames leaves the
//   first files new and the others old (the window is a few rename() calls, microseconds); and if one rename
//   fails (it should not: the targets were checked), the ones before it are already new (the error says which).
// - Temporaries are removed on SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXFSZ and SIGXCPU (the file-size and CPU-time
//   limits): while any exists, a handler (installed
//   only where the signal's disposition is the default) unlinks every registered temporary and re-raises the
//   signal with its default action, so the exit status still says "killed by signal". Temporaries other threads
//   are creating at that moment are waited for and removed too, and none is created after it (the creator throws).
//   Programs with their own handlers can call remove_registered_temporaries() (async-signal-safe) from them. At most
//   kMaxRegisteredTemporaries temporaries at a time are registered (more still work, but are not removed on a
//   signal). A program writing a temporary by name (ffmpeg, run_program) is killed and reaped first, so that it cannot
//   create its file again. SIGKILL cannot be caught: after one, "*.tmp-*" siblings may remain.
#pragma once

#include <fcntl.h>
#include <linux/fs.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/random.h>
#include <time.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <ostream>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace grtrace {

// ---- path checks ----------------------------------------------------------------------------------------

/// What kind of directory entry `s` is, for a message ("a character device", "a FIFO", ...).
inline const char* entry_kind_name(const std::filesystem::file_status& s) {
  namespace fs = std::filesystem;
  switch (s.type()) {
    case fs::file_type::directory: return "a directory";
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::fifo: return "a FIFO (named pipe)";
    case fs::file_type::socket: return "a socket";
    case fs::file_type::symlink: return "a symbolic link";
    case fs::file_type::regular: return "a regular file";
    default: return "not a regular file";
  }
}

namespace detail {
/// The inode flags (chattr: FS_IMMUTABLE_FL, FS_APPEND_FL, ...) of the file or directory at `p`, without following
/// a link there; 0 where they cannot be read (no such entry, no permission, a file system without them).
inline int inode_flags(const std::filesystem::path& p, bool directory) {
  const int fd = ::open(p.c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC | (directory ? O_DIRECTORY : 0));
  if (fd < 0) return 0;
  int flags = 0;  // the kernel reads and writes an int, whatever FS_IOC_GETFLAGS's declared size
  const int rc = ::ioctl(fd, FS_IOC_GETFLAGS, &flags);
  ::close(fd);
  return rc == 0 ? flags : 0;
}

/// Which of the flags that forbid replacing an entry `flags` holds, as chattr names it; nullptr for neither.
inline const char* rename_forbidding_flag(int flags) {
  if (flags & FS_IMMUTABLE_FL) return "immutable (chattr +i)";
  if (flags & FS_APPEND_FL) return "append-only (chattr +a)";
  return nullptr;
}
}  // namespace detail

/// Throws std::runtime_error with a message naming the path when `target` cannot be created: an empty name, a
/// name longer than the directory allows, its directory is missing, is not a directory, or is not writable, or
/// `target` exists as something other than a regular file or a symbolic link (a directory, a device, a FIFO, a
/// socket: renaming a file over it would replace, say, /dev/null for the whole system), or `target` or its
/// directory is immutable or append-only (chattr +i / +a). Creates nothing.
inline void check_output_path(const std::filesystem::path& target) {
  namespace fs = std::filesystem;
  if (target.empty() || !target.has_filename() || target.filename() == "." || target.filename() == "..")
    throw std::runtime_error("cannot write '" + target.string() + "': not a file name");
  // The system refuses longer paths whole (ENAMETOOLONG), which the checks below would misreport as a missing
  // directory; the temporary beside the target is 21 bytes longer (".tmp-" and 16 characters).
  if (const std::size_t n = target.native().size(); n + 21 >= PATH_MAX)
    throw std::runtime_error("cannot write '" + target.string().substr(0, 60) + "...': its path is " +
                             std::to_string(n) + " bytes long, more than the " + std::to_string(PATH_MAX - 22) +
                             " this system allows for an output; choose a shorter path");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::exists(dir, ec))
    throw std::runtime_error("cannot write '" + target.string() + "': directory '" + dir.string() + "' does not exist");
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error("cannot write '" + target.string() + "': '" + dir.string() + "' is not a directory");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw std::runtime_error("cannot write '" + target.string() + "': directory '" + dir.string() +
                             "' is not writable");
  const long dir_name_max = ::pathconf(dir.c_str(), _PC_NAME_MAX);
  const std::size_t name_max = dir_name_max > 0 ? static_cast<std::size_t>(dir_name_max) : 255;
  if (const std::size_t n = target.filename().string().size(); n > name_max)
    throw std::runtime_error("cannot write '" + target.string() + "': its file name is " + std::to_string(n) +
                             " bytes long, more than the " + std::to_string(name_max) +
                             " its directory allows; choose a shorter name");
  // The entry itself, not what a link there points to: a link is replaced by the rename, never followed.
  const fs::file_status entry = fs::symlink_status(target, ec);
  if (fs::is_directory(target, ec))
    throw std::runtime_error("cannot write '" + target.string() + "': it is a directory");
  if (fs::exists(entry) && !fs::is_regular_file(entry) && !fs::is_symlink(entry))
    throw std::runtime_error("cannot write '" + target.string() + "': it is " + entry_kind_name(entry) +
                             ", not a regular file; name a regular file (a new one, or one to replace)");
  // The inode flags (chattr) the permission bits do not show, even to root: an immutable or append-only file cannot
  // be replaced, and an append-only directory keeps the temporary's name, so the rename that finishes the output
  // would fail after all the work.
  if (const char* flag =
          fs::is_regular_file(entry) ? detail::rename_forbidding_flag(detail::inode_flags(target, false)) : nullptr)
    throw std::runtime_error("cannot write '" + target.string() + "': it is " + flag +
                             ", so it cannot be replaced; clear the flag (chattr -i / -a) or choose another name");
  if (const char* flag = detail::rename_forbidding_flag(detail::inode_flags(dir, true)))
    throw std::runtime_error("cannot write '" + target.string() + "': directory '" + dir.string() + "' is " + flag +
                             ": an output is written beside its name and renamed into place, which it refuses; "
                             "choose another directory");
}

namespace detail {
/// The directory entry an output replaces: its directory resolved (links included), its own name not (rename()
/// replaces a link there, it does not write through it).
inline std::filesystem::path entry_of(const std::filesystem::path& p) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path abs = fs::absolute(p, ec);
  return fs::weakly_canonical(abs.parent_path(), ec) / abs.filename();
}
}  // namespace detail

/// True when writing the output `a` (by rename, see below) would replace the file `b`: the same directory entry,
/// or `b` resolved through its links is that entry. Two outputs of one run, or an output and an input, must
/// never be the same in this sense.
inline bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  namespace fs = std::filesystem;
  const fs::path entry = detail::entry_of(a);
  if (entry == detail::entry_of(b)) return true;
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return !ec && entry == resolved;
}

// ---- removal of temporaries on a signal ------------------------------------------------------------------

inline constexpr std::size_t kMaxRegisteredTemporaries = 64;

namespace detail {

inline constexpr std::size_t kTemporaryPathMax = 4096;
struct TemporarySlot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 registered
  std::array<char, kTemporaryPathMax> path{};
};
inline std::array<TemporarySlot, kMaxRegisteredTemporaries> g_temporary_slots{};
// The signals that end a process by default and can be caught: the user's (INT, TERM, HUP, QUIT) and the system's
// limits (XFSZ: a write beyond RLIMIT_FSIZE; XCPU: the soft CPU-time limit).
inline constexpr std::array<int, 6> kCleanupSignals = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXFSZ, SIGXCPU};
// A program this process runs that writes a temporary by name (ffmpeg writing the MP4): ended and reaped before the
// temporaries are removed, or it would create its file again after the removal (run_program, flight_files.hpp).
inline std::atomic<pid_t> g_writing_child{0};
// While an OutputSet renames its files: a cleanup signal delivered to any thread is only noted here, and acted on
// (removal, re-raise) once the whole set is in place.
inline std::atomic<int> g_committing{0};
inline std::atomic<int> g_pending_signal{0};
// Set once the temporaries are being removed for good (a signal is ending the process): no thread creates another.
inline std::atomic<int> g_ending{0};
// Threads between "decided to create a temporary" and "registered it" (signals blocked in them). The removal
// waits for them, so a temporary created while another thread handles the signal is registered before the scan.
// Sequentially consistent on both sides (Dekker): either the creator sees g_ending and creates nothing, or the
// remover sees the creator and waits until its temporary is registered.
inline std::atomic<int> g_creating{0};

/// Waits (spinning; at most ~2 s) until no thread is between creating and registering a temporary.
/// Async-signal-safe: atomics and clock_gettime() only.
inline void wait_for_temporary_creations() noexcept {
  timespec start{}, now{};
  ::clock_gettime(CLOCK_MONOTONIC, &start);
  while (g_creating.load() != 0) {
    ::clock_gettime(CLOCK_MONOTONIC, &now);
    if (now.tv_sec - start.tv_sec > 2) return;  // a creator stuck in open() (a hung network file system)
  }
}

}  // namespace detail

/// Unlinks every registered temporary, for good: from the first call on, no thread creates another temporary
/// (TemporaryOutput throws), and temporaries other threads are creating at that moment are waited for and removed
/// too. For a process about to end on a signal. Async-signal-safe (atomics, clock_gettime() and unlink()).
inline void remove_registered_temporaries() noexcept {
  const int saved = errno;
  detail::g_ending.store(1);
  if (const pid_t child = detail::g_writing_child.exchange(0); child > 0) {
    ::kill(child, SIGKILL);
    while (::waitpid(child, nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  detail::wait_for_temporary_creations();
  for (auto& slot : detail::g_temporary_slots)
    if (slot.state.load() == 2) ::unlink(slot.path.data());
  errno = saved;
}

namespace detail {

extern "C" inline void grtrace_temporary_cleanup_handler(int sig);

inline void install_cleanup_handler(int sig) {
  struct sigaction sa{};
  sa.sa_handler = &grtrace_temporary_cleanup_handler;
  ::sigemptyset(&sa.sa_mask);
  for (const int other : kCleanupSignals) ::sigaddset(&sa.sa_mask, other);
  sa.sa_flags = static_cast<int>(SA_RESETHAND);
  ::sigaction(sig, &sa, nullptr);
}

/// Removes every temporary and ends the process with `sig`'s default action (delivered when the calling thread
/// unblocks it: at the handler's return, or at the end of OutputSet::commit()). Async-signal-safe.
inline void remove_temporaries_and_raise(int sig) noexcept {
  remove_registered_temporaries();
  struct sigaction dfl{};
  dfl.sa_handler = SIG_DFL;
  ::sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  ::raise(sig);
}

extern "C" inline void grtrace_temporary_cleanup_handler(int sig) {
  if (g_committing.load() != 0) {  // a set is being renamed: the committer ends the process once it is in place
    g_pending_signal.store(sig);
    install_cleanup_handler(sig);  // SA_RESETHAND removed it
    // Looked at again after the store (Dekker with commit(): its decrement, then its look at the pending signal):
    // if the set finished in between, whoever takes the pending signal back ends the process; nobody loses it.
    if (g_committing.load() != 0 || g_pending_signal.exchange(0) == 0) return;
  }
  remove_temporaries_and_raise(sig);
}

inline void install_temporary_cleanup_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int sig : kCleanupSignals) {
      struct sigaction old{};
      if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL || (old.sa_flags & SA_SIGINFO) != 0)
        continue;  // ignored (e.g. nohup) or handled by the program: leave it alone
      install_cleanup_handler(sig);
    }
  });
}

/// Registers `path` for removal on a signal; returns the slot, or -1 if all slots are taken.
inline int register_temporary(const std::string& path) {
  if (path.size() >= kTemporaryPathMax) return -1;
  for (std::size_t i = 0; i < g_temporary_slots.size(); ++i) {
    int expected = 0;
    auto& slot = g_temporary_slots[i];
    if (slot.state.compare_exchange_strong(expected, 1, std::memory_order_acq_rel)) {
      std::memcpy(slot.path.data(), path.c_str(), path.size() + 1);
      slot.state.store(2, std::memory_order_release);
      return static_cast<int>(i);
    }
  }
  return -1;
}

inline void unregister_temporary(int slot) {
  if (slot >= 0) g_temporary_slots[static_cast<std::size_t>(slot)].state.store(0, std::memory_order_release);
}

/// 16 characters from [a-z0-9] drawn from getrandom() (the kernel's CSPRNG).
inline std::string random_suffix() {
  static constexpr char kAlphabet[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  std::array<unsigned char, 16> bytes{};
  std::size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::getrandom(bytes.data() + got, bytes.size() - got, 0);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::system_error(errno, std::generic_category(), "getrandom");
    }
    got += static_cast<std::size_t>(n);
  }
  std::string s;
  for (const unsigned char b : bytes) s += kAlphabet[b % (sizeof kAlphabet - 1)];
  return s;
}

/// An std::streambuf writing to a file descriptor (seekable: OpenEXR seeks back to write its offset table).
class FdStreamBuf : public std::streambuf {
 public:
  explicit FdStreamBuf(int fd) : fd_(fd), buffer_(1 << 16) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  FdStreamBuf(const FdStreamBuf&) = delete;
  FdStreamBuf& operator=(const FdStreamBuf&) = delete;
  /// The errno of the first failed write (0 if none).
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!flush_buffer()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return flush_buffer() ? 0 : -1; }
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
    if (!flush_buffer()) return pos_type(off_type(-1));
    const int whence = dir == std::ios_base::beg ? SEEK_SET : dir == std::ios_base::cur ? SEEK_CUR : SEEK_END;
    const off_t r = ::lseek(fd_, static_cast<off_t>(off), whence);
    return r < 0 ? pos_type(off_type(-1)) : pos_type(static_cast<off_type>(r));
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode mode) override {
    return seekoff(off_type(pos), std::ios_base::beg, mode);
  }

 private:
  bool flush_buffer() {
    const char* p = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0) {
      const ssize_t n = ::write(fd_, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        if (error_ == 0) error_ = errno;
        return false;
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return true;
  }

  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

}  // namespace detail

// ---- one temporary output ----------------------------------------------------------------------------------

/// An exclusively created, unpredictable temporary beside `target` (see the file comment), open for writing.
/// Destroying it without commit() removes the temporary and leaves `target` as it was.
class TemporaryOutput {
 public:
  /// check_output_path(target), then creates the temporary. Throws std::runtime_error naming the target.
  explicit TemporaryOutput(std::filesystem::path target) : target_(std::move(target)) {
    check_output_path(target_);
    std::string name = target_.filename().string();
    if (name.size() > 200) name.resize(200);  // keep "<name>.tmp-<16>" under NAME_MAX
    const std::filesystem::path dir = target_.has_parent_path() ? target_.parent_path() : std::filesystem::path(".");
    for (int attempt = 0; attempt < 100; ++attempt) {
      const std::filesystem::path candidate = dir / (name + ".tmp-" + detail::random_suffix());
      detail::install_temporary_cleanup_handlers();
      // Signals blocked between creating and registering: a signal then cannot leave the file behind.
      sigset_t block, old;
      ::sigemptyset(&block);
      for (const int sig : detail::kCleanupSignals) ::sigaddset(&block, sig);
      ::pthread_sigmask(SIG_BLOCK, &block, &old);
      detail::g_creating.fetch_add(1);  // before looking at g_ending: see detail::g_creating
      if (detail::g_ending.load() != 0) {
        detail::g_creating.fetch_sub(1);
        ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
        throw std::runtime_error("cannot write '" + target_.string() + "': the program is ending on a signal");
      }
      fd_ = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
      const int err = errno;
      if (fd_ >= 0) slot_ = detail::register_temporary(candidate.string());
      detail::g_creating.fetch_sub(1);
      ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
      if (fd_ >= 0) {
        temporary_ = candidate;
        buf_ = std::make_unique<detail::FdStreamBuf>(fd_);
        stream_ = std::make_unique<std::ostream>(buf_.get());
        return;
      }
      if (err != EEXIST)
        throw std::runtime_error("cannot write '" + target_.string() + "': cannot create a temporary file in '" +
                                 dir.string() + "': " + std::strerror(err));
    }
    throw std::runtime_error("cannot write '" + target_.string() + "': no free temporary name after 100 attempts");
  }
  TemporaryOutput(const TemporaryOutput&) = delete;
  TemporaryOutput& operator=(const TemporaryOutput&) = delete;
  ~TemporaryOutput() { discard(); }

  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporary() const { return temporary_; }
  /// The open descriptor (for writers that take one; do not close it).
  int fd() const { return fd_; }
  /// A stream on the descriptor (seekable).
  std::ostream& stream() { return *stream_; }

  /// Writes raw bytes through the stream.
  void write(const void* data, std::size_t size) {
    stream_->write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  }

  /// Flushes and closes the temporary; throws std::runtime_error naming the target if any write failed
  /// (e.g. a full disk). Idempotent.
  void finish() {
    if (fd_ < 0) {
      if (!finished_) throw std::runtime_error("cannot write '" + target_.string() + "': the temporary was discarded");
      return;
    }
    stream_->flush();
    const int write_error = buf_->error();
    const bool stream_bad = !*stream_;
    const int fd = std::exchange(fd_, -1);
    const int close_result = ::close(fd);
    const int close_errno = errno;
    finished_ = true;
    if (write_error != 0 || stream_bad || close_result != 0) {
      const int e = write_error != 0 ? write_error : close_result != 0 ? close_errno : EIO;
      discard();
      throw std::runtime_error("failed while writing '" + target_.string() + "': " + std::strerror(e));
    }
  }

  /// finish(), then renames the temporary over the target. Throws std::runtime_error naming the target (the
  /// temporary is removed, so its name would tell the user nothing; discard() clears it, and the message used to
  /// read "cannot rename '' to ...").
  void commit() {
    finish();
    if (committed_) return;
    if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
      const int e = errno;
      discard();
      throw std::runtime_error("cannot put the finished file in place at '" + target_.string() + "': " +
                               std::strerror(e) + " (the file there is unchanged)");
    }
    committed_ = true;
    detail::unregister_temporary(std::exchange(slot_, -1));
  }

  /// Closes and removes the temporary (no-op after commit()).
  void discard() noexcept {
    if (fd_ >= 0) ::close(std::exchange(fd_, -1));
    if (!committed_ && !temporary_.empty()) {
      ::unlink(temporary_.c_str());
      temporary_.clear();
    }
    detail::unregister_temporary(std::exchange(slot_, -1));
  }

 private:
  std::filesystem::path target_, temporary_;
  int fd_ = -1;
  int slot_ = -1;
  bool finished_ = false, committed_ = false;
  std::unique_ptr<detail::FdStreamBuf> buf_;
  std::unique_ptr<std::ostream> stream_;
};

// ---- a set of outputs committed together -------------------------------------------------------------------

/// The outputs of one run: add() creates each temporary (write it, then finish() or leave it to commit()),
/// commit() renames them all with the cleanup signals blocked. Destroying the set without commit() removes
/// every temporary: no output is changed unless all of them could be written.
class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Checks every target (check_output_path) and that no two are the same file, creating nothing. Call it
  /// before the work so a bad path is refused before the time is spent.
  static void check_paths(const std::vector<std::filesystem::path>& targets) {
    for (std::size_t i = 0; i < targets.size(); ++i) {
      check_output_path(targets[i]);
      for (std::size_t j = 0; j < i; ++j)
        if (same_file(targets[i], targets[j]))
          throw std::runtime_error("cannot write '" + targets[i].string() + "' twice in one run");
    }
  }

  /// A new temporary for `target` (throws std::runtime_error when the target is unusable or already in the set).
  TemporaryOutput& add(const std::filesystem::path& target) {
    for (const auto& o : outputs_)
      if (same_file(o->target(), target))
        throw std::runtime_error("cannot write '" + target.string() + "' twice in one run");
    outputs_.push_back(std::make_unique<TemporaryOutput>(target));
    return *outputs_.back();
  }

  /// Finishes every temporary (any write error: all are removed, nothing changed, the error propagates), then
  /// renames them in the order added with the cleanup signals blocked.
  void commit() {
    try {
      for (auto& o : outputs_) o->finish();
    } catch (...) {
      outputs_.clear();
      throw;
    }
    sigset_t block, old;
    ::sigemptyset(&block);
    for (const int sig : detail::kCleanupSignals) ::sigaddset(&block, sig);
    ::pthread_sigmask(SIG_BLOCK, &block, &old);
    detail::g_committing.fetch_add(1, std::memory_order_acq_rel);  // other threads' signals wait too
    std::string renamed;
    std::string error;
    try {
      for (auto& o : outputs_) {
        o->commit();
        renamed += (renamed.empty() ? "" : ", ") + o->target().string();
      }
    } catch (const std::exception& e) {
      error = std::string(e.what()) + (renamed.empty() ? "" : " (already replaced: " + renamed + ")");
    }
    outputs_.clear();
    if (detail::g_committing.fetch_sub(1) == 1) {
      if (const int sig = detail::g_pending_signal.exchange(0))  // the signal that came during the renames
        detail::remove_temporaries_and_raise(sig);
    }
    ::pthread_sigmask(SIG_SETMASK, &old, nullptr);  // a signal raised above is delivered here
    if (!error.empty()) throw std::runtime_error(error);
  }

  std::size_t size() const { return outputs_.size(); }

 private:
  std::vector<std::unique_ptr<TemporaryOutput>> outputs_;
};

/// Writes `target` whole or not at all: write(std::ostream&) fills an exclusively created temporary (see the
/// file comment), which is then renamed over `target`. On any failure (an exception from `write`, a write
/// error, the rename) the temporary is removed, `target` is left as it was, and the exception propagates
/// (I/O failures as std::runtime_error naming the target). `write` must throw if it could not write it all.
template <class WriteFn>
void write_file_atomically(const std::filesystem::path& target, WriteFn&& write) {
  TemporaryOutput out(target);
  std::forward<WriteFn>(write)(out.stream());
  out.commit();
}

/// The same into a set (committed with the set).
template <class WriteFn>
void write_file_atomically(OutputSet& set, const std::filesystem::path& target, WriteFn&& write) {
  TemporaryOutput& out = set.add(target);
  std::forward<WriteFn>(write)(out.stream());
  out.finish();
}

}  // namespace grtrace
