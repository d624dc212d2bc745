#include "python/job_runner.h"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace py = pybind11;

namespace tray::python {
namespace {

/// What the render thread and the waiting Python thread share.
struct Exchange {
  std::mutex mutex;
  std::condition_variable changed;
  double fraction = 0;
  bool fractionNew = false;
  std::vector<std::string> warnings;
  bool done = false;
  std::atomic<bool> stop{false};
  std::optional<RenderJobResult> result;
  std::exception_ptr error;
};

/// How often the waiting thread looks for signals when nothing else happens: Python runs its
/// signal handlers (KeyboardInterrupt) only on the main thread, from PyErr_CheckSignals.
constexpr auto kPoll = std::chrono::milliseconds(50);

}  // namespace

RenderJobResult runJob(const RenderJob& job, const py::object& progress,
                       const GltfDocument* document, KeptScene* kept, double* setupSeconds,
                       PreviewServer* preview) {
  Exchange x;
  RenderJobEvents events;
  const auto start = std::chrono::steady_clock::now();
  double setup = 0;
  events.started = [&setup, start] {
    setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  events.warning = [&x](const std::string& w) {
    std::lock_guard lock(x.mutex);
    x.warnings.push_back(w);
    x.changed.notify_one();
  };
  events.progress = [&x](double f) {
    std::lock_guard lock(x.mutex);
    x.fraction = f, x.fractionNew = true;
    x.changed.notify_one();
  };
  events.stop = &x.stop;
  if (preview) preview->attach(events, job);

  std::optional<py::error_already_set> pythonError;  // the first: it stopped the render
  auto stopWith = [&](py::error_already_set&& e) {
    if (!pythonError) pythonError.emplace(std::move(e));
    x.stop = true;
  };
  std::thread worker;
  {
    py::gil_scoped_release release;
    worker = std::thread([&x, &job, &events, document, kept] {
      try {
        RenderJobResult r = runRenderJob(job, events, document, kept);
        std::lock_guard lock(x.mutex);
        x.result.emplace(std::move(r));
      } catch (...) {
        std::lock_guard lock(x.mutex);
        x.error = std::current_exception();
      }
      std::lock_guard lock(x.mutex);
      x.done = true;
      x.changed.notify_one();
    });
  }
  for (bool done = false; !done;) {
    std::vector<std::string> warnings;
    std::optional<double> fraction;
    {
      py::gil_scoped_release release;
      std::unique_lock lock(x.mutex);
      x.changed.wait_for(lock, kPoll,
                         [&x] { return x.done || x.fractionNew || !x.warnings.empty(); });
      warnings.swap(x.warnings);
      if (x.fractionNew) fraction = x.fraction, x.fractionNew = false;
      done = x.done;
    }
    for (const std::string& w : warnings)  // -W error makes a warning an exception
      if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) != 0) stopWith(py::error_already_set());
    if (fraction && !progress.is_none() && !pythonError) {
      try {
        progress(*fraction);
      } catch (py::error_already_set& e) {
        stopWith(std::move(e));
      }
    }
    if (PyErr_CheckSignals() != 0) stopWith(py::error_already_set());
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (setupSeconds) *setupSeconds = setup;
  if (pythonError) throw std::move(*pythonError);
  if (x.error) std::rethrow_exception(x.error);
  if (preview && x.result->image) {
    const RenderJobResult& r = *x.result;
    preview->publishFinal(r.image->film, r.stats.passes > 0
                                             ? double(r.stats.samples) / double(r.pixels)
                                             : double(job.settings.getInt("spp")));
  }
  return std::move(*x.result);
}

}  // namespace tray::python
