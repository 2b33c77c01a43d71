// A real small disk for tests of full-disk handling: a tmpfs of a few MiB
// mounted in a mount namespace of this test process alone (root, or a user
// namespace where the kernel allows one). Use it in a test process of its
// own (gtest_discover_tests runs each test in one): the namespace stays.
#pragma once

#include <sched.h>
#include <sys/mount.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace rrlab::test {

// A private tmpfs of `mib` MiB at a new temporary directory.
class SmallDisk {
 public:
  explicit SmallDisk(int mib) {
    const uid_t uid = getuid();
    const gid_t gid = getgid();
    if (unshare(uid == 0 ? CLONE_NEWNS : CLONE_NEWNS | CLONE_NEWUSER) != 0) {
      error_ = std::string("unshare: ") + std::strerror(errno);
      return;
    }
    if (uid != 0) {  // map ourselves to root in the new user namespace
      std::ofstream("/proc/self/setgroups") << "deny";
      std::ofstream("/proc/self/uid_map") << "0 " << uid << " 1";
      std::ofstream("/proc/self/gid_map") << "0 " << gid << " 1";
    }
    mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr);  // nothing propagates out
    std::string pattern = "/tmp/rrlab-small-disk-XXXXXX";
    if (!mkdtemp(pattern.data())) {
      error_ = "mkdtemp failed";
      return;
    }
    dir_ = pattern;
    const std::string options = "size=" + std::to_string(mib) + "m";
    if (mount("tmpfs", dir_.c_str(), "tmpfs", 0, options.c_str()) != 0)
      error_ = std::string("mount tmpfs: ") + std::strerror(errno);
  }
  ~SmallDisk() {
    if (!dir_.empty()) {
      umount2(dir_.c_str(), MNT_DETACH);
      std::filesystem::remove_all(dir_);
    }
  }
  const std::string& error() const { return error_; }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  std::int64_t free_bytes() const {
    struct statvfs s {};
    statvfs(dir_.c_str(), &s);
    return std::int64_t(s.f_bavail) * std::int64_t(s.f_frsize);
  }

 private:
  std::string dir_, error_;
};

// Writes a file until the disk refuses more: what else filled the disk.
inline void fill_with_a_file(const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  const std::string block(64 << 10, 'x');
  while (out.write(block.data(), std::streamsize(block.size())) && out.flush()) {
  }
}

}  // namespace rrlab::test
