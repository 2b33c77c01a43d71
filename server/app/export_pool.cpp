#include <rrlab/server/app/export_pool.hpp>

namespace rrlab::server {

std::shared_ptr<ExportPool::Ticket> ExportPool::reserve(std::size_t bytes) {
  {
    std::lock_guard lock(mutex_);
    if (reserved_ + bytes > budget_) return nullptr;
    reserved_ += bytes;
  }
  return std::make_shared<Ticket>(*this, bytes);
}

void ExportPool::release(std::size_t bytes) {
  std::lock_guard lock(mutex_);
  reserved_ -= bytes;
}

std::size_t ExportPool::reserved() const {
  std::lock_guard lock(mutex_);
  return reserved_;
}

}  // namespace rrlab::server
