#pragma once
// Small fixtures shared by the facemesh tests.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "emoface/core/io.hpp"
#include "emoface/facemesh/mesh.hpp"

namespace emoface::facemesh::testing {

/// A closed tetrahedron with outward (counter-clockwise) faces.
inline Mesh tetrahedron() {
  Mesh m;
  m.vertices.resize(4, 3);
  m.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.faces.resize(4, 3);
  m.faces << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return m;
}

/// A per-test temporary directory, removed afterwards.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("emoface_facemesh_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  /// Writes `bytes` to `name` in the test's directory; returns its path.
  std::string put(const std::string& name, const std::string& bytes) const {
    core::write_file_atomic(path(name), bytes);
    return path(name);
  }
  std::filesystem::path dir_;
};

}  // namespace emoface::facemesh::testing
