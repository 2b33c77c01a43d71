// A fresh database path in its own temporary folder per test, removed after,
// and a minimal run to store.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <string>

#include <rrlab/storage/run_store.hpp>

namespace rrlab::storage {

class TempStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = "/tmp/rrlab-store-XXXXXX";
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    path_ = dir_ + "/test.db";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  static NewRun new_run(const std::string& method = "pinv") {
    NewRun r;
    r.scenario_name = "demo";
    r.scenario_json = "{}";
    r.method = method;
    r.params_json = "{}";
    r.mode = "batch";
    r.dof = 3;
    return r;
  }
  std::string dir_, path_;
};

}  // namespace rrlab::storage
