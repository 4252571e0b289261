// grtrace._grtrace: the Python module's compiled part, a thin client of the application library's front door
// (grtrace/app/front_door.hpp). Keywords are the tools' option names with underscores (camera_r for --camera-r),
// read and refused by the library's own reader (app::read_render_request), so a bad argument raises ValueError
// with the message grtrace-render prints. A frame's channels are numpy arrays over the library's own buffers (no
// copy; the Frame object stays alive while an array does). Rendering runs on a thread of its own with the GIL
// released; the calling thread waits in slices of 20 ms, checking for signals (Ctrl-C stops the render between
// tiles and raises KeyboardInterrupt) and calling the progress callback.
#include "grtrace/app/front_door.hpp"
#include "grtrace/core/memory_limit.hpp"
#include "grtrace/core/number_text.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/frame_files.hpp"
#include "grtrace/version.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <variant>
#include <vector>

namespace py = pybind11;
using namespace grtrace;

namespace {

/// A refusal of the caller's input: raised as ValueError with the library's message.
struct InputError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// ---- keywords -> option texts ---------------------------------------------------------------------------

/// The text the library reads for one keyword's value: numbers as Python writes them (repr: the same double back),
/// sequences as comma-separated numbers, strings as they are. Flags are given when true.
std::string option_text(const std::string& keyword, const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "1" : "0";
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) return py::repr(value).cast<std::string>();
  if (py::hasattr(value, "__float__") && !py::isinstance<py::sequence>(value))  // numpy scalars
    return shortest_number_text(value.cast<double>());
  if (py::isinstance<py::sequence>(value) || py::hasattr(value, "__iter__")) {
    std::string out;
    for (const py::handle item : value) {
      if (!out.empty()) out += ",";
      if (!py::isinstance<py::int_>(item) && !py::isinstance<py::float_>(item) && !py::hasattr(item, "__float__"))
        throw InputError(keyword + " expects numbers, got " + py::repr(value).cast<std::string>());
      out += shortest_number_text(item.cast<double>());
    }
    return out;
  }
  throw InputError(keyword + " expects a number, a string or a sequence of numbers, got " +
                   py::repr(value).cast<std::string>());
}

/// The keyword of an option name: dashes become underscores (camera-r -> camera_r; lambda -> lambda_).
std::string option_name_to_keyword(std::string_view option) {
  std::string keyword(option);
  for (char& c : keyword)
    if (c == '-') c = '_';
  if (keyword == "lambda") keyword += '_';
  return keyword;
}

/// The option name of a keyword: underscores become dashes (camera_r -> camera-r), and a trailing one goes (lambda_
/// -> lambda: the name Python keeps for itself).
std::string option_name(std::string keyword) {
  if (keyword.size() > 1 && keyword.back() == '_') keyword.pop_back();
  for (char& c : keyword)
    if (c == '_') c = '-';
  return keyword;
}

bool is_flag(const std::string& name) {
  for (const app::OptionInfo& o : app::render_options())
    if (o.name == name) return o.flag;
  return false;
}

/// Python keywords as the library's option source. Unknown keywords are refused, naming the known ones' list.
class KeywordOptions : public app::OptionSource {
 public:
  explicit KeywordOptions(const py::dict& kwargs) {
    for (const auto& [key, value] : kwargs) {
      const std::string keyword = key.cast<std::string>();
      const std::string name = option_name(keyword);
      bool known = false;
      for (const app::OptionInfo& o : app::render_options()) known = known || o.name == name;
      if (!known)
        throw InputError("unknown option '" + keyword +
                         "' (grtrace.options() lists them, e.g. camera_r for "
                         "grtrace-render's --camera-r)");
      if (value.is_none()) continue;  // None: the default
      if (is_flag(name)) {
        if (!py::isinstance<py::bool_>(value) && !py::isinstance<py::int_>(value))
          throw InputError(keyword + " is a flag: True or False, got " + py::repr(value).cast<std::string>());
        if (value.cast<bool>()) given_[name] = "1";
        continue;
      }
      given_[name] = option_text(keyword, value);
    }
  }
  bool given(const std::string& name) const override { return given_.count(name) > 0; }
  std::optional<std::string> text(const std::string& name) const override {
    if (auto it = given_.find(name); it != given_.end()) return it->second;
    return std::nullopt;
  }

 private:
  std::map<std::string, std::string> given_;
};

/// The library's checked request of Python keywords (InputError: the tools' message).
app::CheckedRequest checked_request(const py::dict& kwargs) {
  const KeywordOptions options(kwargs);
  try {
    return app::check_request(app::read_render_request(options));
  } catch (const MemoryLimitError& e) {
    throw InputError(e.what());
  }
}

// ---- frames ---------------------------------------------------------------------------------------------

/// A frame as Python sees it: the image (channels and header) and, for a render, its report and request.
struct PyFrame {
  Image image;
  std::optional<app::RenderReport> report;
  std::optional<app::CheckedRequest> checked;
};

/// A channel as a (height, width) float32 array over the frame's own buffer (no copy).
py::array channel_array(py::object frame_object, const std::string& name) {
  PyFrame& frame = frame_object.cast<PyFrame&>();
  if (!frame.image.has_channel(name)) {
    std::string names;
    for (const auto& n : frame.image.channel_names()) names += (names.empty() ? "" : ", ") + n;
    throw py::key_error("no channel '" + name + "' (the frame has " + names + ")");
  }
  std::vector<float>& data = frame.image.channel(name);
  const auto w = static_cast<py::ssize_t>(frame.image.width()), h = static_cast<py::ssize_t>(frame.image.height());
  return py::array(py::dtype::of<float>(), {h, w},
                   {w * static_cast<py::ssize_t>(sizeof(float)), static_cast<py::ssize_t>(sizeof(float))}, data.data(),
                   frame_object);
}

/// Report entries (app::report_entries, app::LineProfileResult::report) as a dict: the tool's JSON line's keys.
py::dict entries_dict(const std::vector<app::ReportEntry>& entries) {
  py::dict d;
  for (const app::ReportEntry& e : entries) {
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, app::ReportEntry::Counts>) {
            py::dict counts;
            for (const auto& [name, n] : v) counts[py::str(name)] = n;
            d[py::str(e.key)] = counts;
          } else {
            d[py::str(e.key)] = v;
          }
        },
        e.value);
  }
  return d;
}

py::dict report_dict(const PyFrame& frame) {
  if (!frame.report || !frame.checked) return py::dict();
  py::dict d = entries_dict(app::report_entries(*frame.report, *frame.checked));
  d["setup_seconds"] = frame.report->setup_seconds;
  return d;
}

// ---- rendering on a thread of its own -----------------------------------------------------------------------

/// The threads renders run on, kept between renders: a render on a new thread each time would start a new OpenMP
/// team and new allocator arenas each time (measured: about 5 % of a 256 x 256 Kerr frame). A render takes an idle
/// worker, or starts one when every worker is busy (two Python threads rendering at once). Never destroyed: idle
/// workers wait out the process (joining them at exit would race the interpreter's own shutdown).
class Workers {
 public:
  static Workers& instance() {
    static Workers* workers = new Workers;
    return *workers;
  }

  /// Runs job() on an idle worker; finished() is called on that worker once job has returned. Returns at once.
  void run(std::function<void()> job) {
    Worker* w = nullptr;
    {
      std::lock_guard lock(mutex_);
      for (auto& candidate : workers_)
        if (!candidate->busy) {
          w = candidate.get();
          break;
        }
      if (!w) w = workers_.emplace_back(std::make_unique<Worker>()).get();
      w->busy = true;
    }
    std::lock_guard lock(w->mutex);
    w->job = std::move(job);
    w->wake.notify_one();
  }

 private:
  struct Worker {
    std::mutex mutex;
    std::condition_variable wake;
    std::function<void()> job;
    bool busy = false;  ///< guarded by Workers::mutex_
    std::thread thread{[this] { loop(); }};

    void loop() {
      for (;;) {
        std::function<void()> next;
        {
          std::unique_lock lock(mutex);
          wake.wait(lock, [&] { return static_cast<bool>(job); });
          next = std::move(job);
          job = nullptr;
        }
        next();  // never throws: the job keeps its own exceptions
        std::lock_guard lock(Workers::instance().mutex_);
        busy = false;
      }
    }
  };

  std::mutex mutex_;
  std::vector<std::unique_ptr<Worker>> workers_;
};

/// Runs work() on a worker thread with the GIL released while the calling thread, every 20 ms, checks for signals (a
/// pending KeyboardInterrupt cancels: cancel is set, the work waited for, the exception raised) and calls
/// progress(done, total) where given. Returns what work returned; rethrows what it threw.
template <class Work>
auto run_interruptibly(Work&& work, std::atomic<bool>& cancel, const std::atomic<long>& done, long total,
                       const py::object& progress) {
  using R = decltype(work());
  std::optional<R> result;
  std::exception_ptr error;
  std::mutex mutex;
  std::condition_variable finished_cv;
  bool finished = false;
  {
    py::gil_scoped_release release;
    Workers::instance().run([&] {
      try {
        result.emplace(work());
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard lock(mutex);
      finished = true;
      finished_cv.notify_all();
    });
  }
  const auto wait = [&] {
    py::gil_scoped_release release;
    std::unique_lock lock(mutex);
    finished_cv.wait(lock, [&] { return finished; });
  };
  const auto stop = [&] {
    cancel.store(true);
    wait();
  };
  for (;;) {
    bool over = false;
    {
      py::gil_scoped_release release;
      std::unique_lock lock(mutex);
      over = finished_cv.wait_for(lock, std::chrono::milliseconds(20), [&] { return finished; });
    }
    if (PyErr_CheckSignals() != 0) {
      stop();
      throw py::error_already_set();
    }
    if (!progress.is_none()) {
      try {
        progress(done.load(), total);
      } catch (...) {
        stop();
        throw;
      }
    }
    if (over) break;
  }
  if (error) std::rethrow_exception(error);
  return std::move(*result);
}

PyFrame render(const py::object& progress, const py::dict& kwargs) {
  const app::CheckedRequest checked = checked_request(kwargs);
  std::atomic<bool> cancel{false};
  std::atomic<long> done{0};
  app::RenderControl control;
  control.bar = ProgressMode::never;
  control.cancel = &cancel;
  control.pixels_done = &done;
  const long total = static_cast<long>(checked.camera.width()) * checked.camera.height();
  app::RenderResult result = run_interruptibly([&] { return app::FrameRenderer::create(checked)->render(control); },
                                               cancel, done, total, progress);
  return PyFrame{std::move(result.image), std::move(result.report), checked};
}

// ---- rays -------------------------------------------------------------------------------------------------

/// A sequence of numbers, or InputError(`what`) for anything else.
template <class T>
std::vector<T> numbers_of(const py::object& value, const std::string& what) {
  try {
    return value.cast<std::vector<T>>();
  } catch (const py::cast_error&) {
    throw InputError(what + ", got " + py::repr(value).cast<std::string>());
  }
}

py::dict trace_ray(const py::object& pixel, const py::object& position, const py::object& momentum,
                   int samples_per_step, bool scene_objects, const py::dict& kwargs) {
  const app::CheckedRequest checked = checked_request(kwargs);
  GeodesicState y0;
  std::optional<Vec4> observer;
  if (!pixel.is_none()) {
    if (!position.is_none() || !momentum.is_none())
      throw InputError("give pixel=(column, row), or position= and momentum=, not both");
    const auto p = numbers_of<long>(pixel, "pixel expects (column, row): two whole numbers");
    if (p.size() != 2) throw InputError("pixel expects (column, row)");
    const Camera& camera = checked.camera;
    if (p[0] < 0 || p[1] < 0 || p[0] >= camera.width() || p[1] >= camera.height())
      throw InputError("pixel (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ") is outside the " +
                       std::to_string(camera.width()) + "x" + std::to_string(camera.height()) +
                       " frame (width, height)");
    y0 = camera.pixel_state(static_cast<int>(p[0]), static_cast<int>(p[1]));
    observer = camera.tetrad().e[0];
  } else {
    if (position.is_none() || momentum.is_none())
      throw InputError(
          "give pixel=(column, row) of the camera, or position=(x0..x3) and momentum=(k0..k3) in the "
          "metric's chart");
    const auto x = numbers_of<double>(position, "position expects 4 numbers"),
               k = numbers_of<double>(momentum, "momentum expects 4 numbers");
    if (x.size() != 4 || k.size() != 4) throw InputError("position and momentum expect 4 numbers each");
    y0 << x[0], x[1], x[2], x[3], k[0], k[1], k[2], k[3];
    if (!y0.allFinite()) throw InputError("position and momentum must be finite numbers");
  }
  app::TracedRay ray;
  try {
    py::gil_scoped_release release;
    const auto tracer = app::RayTracer::create(checked);
    app::PathOptions options;
    options.samples_per_step = samples_per_step;
    options.observer_velocity = observer;
    options.scene_objects = scene_objects;
    ray = tracer->trace(y0, options);
  } catch (const app::RequestError& e) {
    throw InputError(e.what());
  }
  const TracedPath& path = ray.path;
  const RayOutcome& outcome = ray.outcome;
  const auto n = static_cast<py::ssize_t>(path.samples.size());
  py::array_t<double> lambda(n), h(n), redshift(n);
  py::array_t<double> x({n, py::ssize_t{4}}), k({n, py::ssize_t{4}}), cartesian({n, py::ssize_t{3}});
  py::array_t<int> step(n);
  auto L = lambda.mutable_unchecked<1>(), H = h.mutable_unchecked<1>(), Z = redshift.mutable_unchecked<1>();
  auto X = x.mutable_unchecked<2>(), K = k.mutable_unchecked<2>(), C = cartesian.mutable_unchecked<2>();
  auto S = step.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const PathSample& s = path.samples[static_cast<std::size_t>(i)];
    L(i) = s.lambda;
    H(i) = s.h;
    Z(i) = s.redshift;
    S(i) = s.step;
    for (py::ssize_t j = 0; j < 4; ++j) {
      X(i, j) = s.state[j];
      K(i, j) = s.state[4 + j];
    }
    for (py::ssize_t j = 0; j < 3; ++j) C(i, j) = s.position[j];
  }
  py::dict d;
  d["lambda"] = lambda;
  d["x"] = x;
  d["k"] = k;
  d["h"] = h;
  d["step"] = step;
  d["cartesian"] = cartesian;
  d["redshift"] = redshift;
  d["status"] = std::string(to_string(path.status));
  py::dict o;
  o["status"] = std::string(to_string(outcome.status));
  o["object"] = ray.object;
  o["radius"] = outcome.radius;
  o["redshift"] = outcome.redshift;
  o["steps"] = outcome.steps;
  o["order"] = outcome.order;
  d["outcome"] = o;
  d["chart"] = ray.cartesian ? "cartesian" : "spherical";
  return d;
}

// ---- line profiles ----------------------------------------------------------------------------------------

/// grtrace.line_profile: the library's reader and checks (app::read_line_profile_request, app::line_profile), the
/// profile computed with the GIL released; numpy copies of the bins (the result is small).
py::dict line_profile_of(const py::dict& kwargs) {
  const KeywordOptions options(kwargs);
  const app::LineProfileRequest request = app::read_line_profile_request(options);
  app::LineProfileResult r;
  {
    py::gil_scoped_release release;
    r = app::line_profile(request);
  }
  const LineProfile& p = r.profile;
  auto array = [](const std::vector<double>& v) {
    return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
  };
  py::dict d;
  d["edges"] = array(p.edges);
  d["flux"] = array(p.flux);
  py::list orders;
  for (const auto& o : p.flux_by_order) orders.append(array(o));
  d["flux_by_order"] = orders;
  d["report"] = entries_dict(r.report);
  d["csv"] = r.csv;
  return d;
}

/// grtrace.ring_image: the library's reader and checks (app::read_ring_image_request, app::ring_image), the image
/// computed with the GIL released; numpy copies of each order's plane.
py::dict ring_image_of(const py::dict& kwargs) {
  const KeywordOptions options(kwargs);
  const app::RingImageRequest request = app::read_ring_image_request(options);
  app::RingImageResult r;
  {
    py::gil_scoped_release release;
    r = app::ring_image(request);
  }
  const RingImage& image = r.rings;
  py::list intensity;
  for (const auto& plane : image.intensity)
    intensity.append(py::array_t<double>(
        {static_cast<py::ssize_t>(image.height), static_cast<py::ssize_t>(image.width)}, plane.data()));
  py::dict d;
  d["intensity"] = intensity;
  d["flux"] = py::array_t<double>(static_cast<py::ssize_t>(image.flux.size()), image.flux.data());
  d["ring_diameter"] = py::array_t<double>(3, image.rings.diameter.data() + 1);
  d["ring_width"] = py::array_t<double>(3, image.rings.width.data() + 1);
  d["report"] = entries_dict(r.report);
  return d;
}

// ---- files ------------------------------------------------------------------------------------------------

PyFrame read_frame(const std::string& path) {
  if (!std::filesystem::exists(path)) throw py::value_error("read_exr: no such file '" + path + "'");
  try {
    py::gil_scoped_release release;
    return PyFrame{read_exr(path), std::nullopt, std::nullopt};
  } catch (const MemoryLimitError& e) {
    throw InputError(std::string("read_exr: ") + e.what());
  } catch (const std::exception& e) {
    throw InputError(std::string("read_exr '") + path + "': " + e.what());
  }
}

void write_frame(const PyFrame& frame, const std::string& path, const std::string& compression, bool preview) {
  const std::string name = std::filesystem::path(path).filename().string();
  if (name.size() < 5 || !name.ends_with(".exr"))
    throw InputError("write_exr: the path must name an .exr file (a name, then .exr), got '" + path + "'");
  ExrWriteOptions options;
  const auto c = exr_compression_from_name(compression);
  if (!c)
    throw InputError("write_exr: unknown compression '" + compression +
                     "'; choose zips, zip, piz, rle or none (lossless: the channels read back bit for bit)");
  options.compression = *c;
  try {
    check_output_path(path);
  } catch (const std::exception& e) {
    throw InputError(std::string("write_exr: ") + e.what());
  }
  py::gil_scoped_release release;
  OutputSet outputs;
  if (preview) write_exr_and_preview(outputs, path, path.substr(0, path.size() - 4) + ".png", frame.image, options);
  else write_exr(outputs, path, frame.image, options);
  outputs.commit();
}

/// A frame of one's own arrays: every array (height, width), float32 after conversion; header strings.
PyFrame frame_of(const py::dict& channels, const py::dict& header) {
  if (channels.empty()) throw InputError("a frame needs at least one channel");
  std::optional<Image> image;
  for (const auto& [key, value] : channels) {
    const std::string name = key.cast<std::string>();
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!a || a.ndim() != 2) throw InputError("channel '" + name + "' must be a 2-d array (height, width)");
    const int h = static_cast<int>(a.shape(0)), w = static_cast<int>(a.shape(1));
    if (!image) {
      if (w < 1 || h < 1) throw InputError("channels must have at least one pixel");
      image.emplace(Image::with_channels(w, h, {}));
    }
    if (w != image->width() || h != image->height())
      throw InputError("channel '" + name + "' is " + std::to_string(h) + "x" + std::to_string(w) + ", the others " +
                       std::to_string(image->height()) + "x" + std::to_string(image->width()));
    std::vector<float>& plane = image->add_channel(name);
    std::copy(a.data(), a.data() + a.size(), plane.begin());
  }
  for (const auto& [key, value] : header) image->metadata[key.cast<std::string>()] = value.cast<std::string>();
  return PyFrame{std::move(*image), std::nullopt, std::nullopt};
}

// ---- what there is ------------------------------------------------------------------------------------------

py::list metrics() {
  py::list out;
  for_each_named_metric([&]<class E>() {
    py::dict m;
    m["name"] = std::string(E::name);
    m["help"] = std::string(E::help);
    m["has_mass"] = E::has_mass;
    py::list charts;
    for (std::string_view c : E::charts) charts.append(std::string(c));
    m["charts"] = charts;
    py::list parameters;
    for (const MetricParameter& p : E::parameters) {
      py::dict d;
      d["name"] = option_name_to_keyword(p.option);
      d["default"] = std::string(p.default_text);
      d["help"] = std::string(p.help);
      parameters.append(d);
    }
    m["parameters"] = parameters;
    out.append(m);
  });
  return out;
}

}  // namespace

PYBIND11_MODULE(_grtrace, m) {
  m.doc() = "grtrace's compiled part: the application library's front door (see the grtrace package)";
  m.attr("__version__") = std::string(kVersion);

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const app::RequestError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const MemoryLimitError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const RenderCancelled& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    }
  });

  py::class_<PyFrame>(m, "Frame", "A rendered (or read) frame: its channels as numpy arrays, header and report.")
      .def_property_readonly("width", [](const PyFrame& f) { return f.image.width(); })
      .def_property_readonly("height", [](const PyFrame& f) { return f.image.height(); })
      .def_property_readonly("channel_names", [](const PyFrame& f) { return f.image.channel_names(); })
      .def("channel", &channel_array, py::arg("name"),
           "The channel as a (height, width) float32 array over the frame's own memory (no copy).")
      .def_property_readonly("header", [](const PyFrame& f) { return f.image.metadata; })
      .def_property_readonly("report", &report_dict)
      .def("write_exr", &write_frame, py::arg("path"), py::arg("compression") = "zips", py::arg("preview") = true,
           "Writes the frame to an OpenEXR file (and its PNG preview beside it), whole or not at all.");

  m.def("_render", &render, py::arg("progress"), py::arg("options"));
  m.def("_trace_ray", &trace_ray, py::arg("pixel"), py::arg("position"), py::arg("momentum"),
        py::arg("samples_per_step"), py::arg("scene_objects"), py::arg("options"));
  m.def("_read_exr", &read_frame, py::arg("path"));
  m.def("_line_profile", &line_profile_of, py::arg("options"));
  m.def("_ring_image", &ring_image_of, py::arg("options"));
  m.def("_frame", &frame_of, py::arg("channels"), py::arg("header"));
  m.def("_options", [] {
    py::list out;
    for (const app::OptionInfo& o : app::render_options()) {
      py::dict d;
      d["name"] = option_name_to_keyword(o.name);
      d["option"] = std::string(o.name);
      d["default"] = std::string(o.default_text);
      d["help"] = std::string(o.help);
      d["flag"] = o.flag;
      out.append(d);
    }
    return out;
  });
  m.def("_metrics", &metrics);
  m.def("_scenes", [] { return app::scene_names(); });
  m.def("_methods", [] {
    py::list out;
    for (const app::ToolMethod& t : app::kToolMethods) {
      py::dict d;
      d["tableau"] = std::string(t.tableau);
      d["control"] = std::string(t.control);
      d["purpose"] = std::string(t.purpose);
      out.append(d);
    }
    return out;
  });
  m.def("_tracers", [] { return std::vector<std::string>(app::kTracerNames.begin(), app::kTracerNames.end()); });
  m.def("_devices", [] { return std::vector<std::string>(app::kDeviceNames.begin(), app::kDeviceNames.end()); });
  m.def("_gpu", [] {
    const app::GpuStatus& g = app::gpu_status();
    py::dict d;
    d["built"] = g.built;
    d["present"] = g.present;
    d["name"] = g.name;
    d["why_not"] = g.why_not;
    return d;
  });
}
