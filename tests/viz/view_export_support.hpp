// tests/viz/view_export_support.hpp
// What the tests of grtrace-view --export share: the tool run without a display, a scratch directory per test
// program and process, a test suite sharing one export run, and the files read back with VTK's XML readers.
// The including test defines GRTRACE_VIEW_EXE.
#pragma once

#include "../common/tool_run.hpp"

#include <gtest/gtest.h>

#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkImageData.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLMultiBlockDataReader.h>

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

#include <filesystem>
#include <set>
#include <string>
#include <unistd.h>

#ifndef GRTRACE_VIEW_EXE
#error "GRTRACE_VIEW_EXE (path of grtrace-view) must be defined by the build"
#endif

namespace grtrace::view_tests {

/// Takes grtrace-view's arguments (shell words); returns the command line that runs it with DISPLAY unset.
inline std::string view(const std::string& args) {
  // Appended in place: GCC 12 flags the chained operator+ on temporaries with a false -Warray-bounds in libstdc++
  // when this unit is read through the tests' precompiled header (GCC bug 105651).
  std::string command = "env -u DISPLAY ";
  command += GRTRACE_VIEW_EXE;
  command += ' ';
  command += args;
  return command;
}

/// Takes the test program's name and a file name; returns the file's path in a scratch directory of that
/// program and this process (created, so parallel test runs do not share it).
inline std::filesystem::path scratch(const std::string& program, const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("grtrace-" + program + "-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

/// Takes a .vtp file; returns what VTK's XML reader makes of it (empty data for a missing file).
inline vtkSmartPointer<vtkPolyData> read_vtp(const std::filesystem::path& file) {
  vtkNew<vtkXMLPolyDataReader> r;
  r->SetFileName(file.c_str());
  r->Update();
  return r->GetOutput();
}

/// Takes a .vti file; returns what VTK's XML reader makes of it (empty data for a missing file).
inline vtkSmartPointer<vtkImageData> read_vti(const std::filesystem::path& file) {
  vtkNew<vtkXMLImageDataReader> r;
  r->SetFileName(file.c_str());
  r->Update();
  return r->GetOutput();
}

/// Takes a scene.vtm; returns the names of its blocks (none for a missing file).
inline std::set<std::string> block_names(const std::filesystem::path& collection) {
  vtkNew<vtkXMLMultiBlockDataReader> r;
  r->SetFileName(collection.c_str());
  r->Update();
  std::set<std::string> names;
  if (auto* blocks = vtkMultiBlockDataSet::SafeDownCast(r->GetOutput()))
    for (unsigned i = 0; i < blocks->GetNumberOfBlocks(); ++i)
      names.insert(blocks->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()));
  return names;
}

/// A test suite whose tests share one run of grtrace-view --export (no display). Takes Run with
/// `static constexpr const char* program, *name` (the scratch directory: scratch(program, name), emptied first)
/// and `static std::string options()` (grtrace-view's other options). Gives the tests dir_ and result_.
template <class Run>
class ExportSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = scratch(Run::program, Run::name);
    std::filesystem::remove_all(dir_);
    result_ = tool_tests::run_command(view(Run::options() + " --export " + dir_.string()));
  }
  inline static std::filesystem::path dir_;
  inline static tool_tests::ToolRun result_;
};

}  // namespace grtrace::view_tests
