// tests/viz/view_export_support.hpp
// What the tests of grtrace-view --export share: the tool run without a display, a scratch directory per test
// program and process, and a .vtp read back with VTK's XML reader. The including test defines GRTRACE_VIEW_EXE.
#pragma once

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

#include <filesystem>
#include <string>
#include <unistd.h>

#ifndef GRTRACE_VIEW_EXE
#error "GRTRACE_VIEW_EXE (path of grtrace-view) must be defined by the build"
#endif

namespace grtrace::view_tests {

/// Takes grtrace-view's arguments (shell words); returns the command line that runs it with DISPLAY unset.
inline std::string view(const std::string& args) {
  return std::string("env -u DISPLAY ") + GRTRACE_VIEW_EXE + " " + args;
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

}  // namespace grtrace::view_tests
