// The outcome of work queued for another thread (an input event for the
// frame writer, a single step for the simulation thread), waited for without
// blocking: the thread that finishes the work settles it once, and the
// callback given to then() runs there, or at once if it has settled already.
// I/O threads hand a callback that posts the reply to their own executor.
#pragma once

#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

namespace rrlab::storage {

enum class StorageFault;  // storage/database.hpp

struct Outcome {
  std::string error;        // "": done
  StorageFault fault{};     // what kind of write failed (other, full, readonly)
  nlohmann::json result;    // what the work answers (a status), null if nothing
  bool ok() const { return error.empty(); }
};

class Completion {
 public:
  using Callback = std::function<void(const Outcome&)>;

  // The first call counts; later ones are ignored.
  void settle(Outcome outcome) {
    Callback callback;
    {
      std::lock_guard lock(mutex_);
      if (settled_) return;
      settled_ = true;
      outcome_ = std::move(outcome);
      callback.swap(callback_);
    }
    if (callback) callback(outcome_);
  }

  // One callback per completion.
  void then(Callback callback) {
    {
      std::lock_guard lock(mutex_);
      if (!settled_) {
        callback_ = std::move(callback);
        return;
      }
    }
    callback(outcome_);
  }

  bool settled() const {
    std::lock_guard lock(mutex_);
    return settled_;
  }

 private:
  mutable std::mutex mutex_;
  bool settled_ = false;
  Outcome outcome_;
  Callback callback_;
};

}  // namespace rrlab::storage
