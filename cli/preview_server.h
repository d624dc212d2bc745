#pragma once
// tray-render --preview: a small HTTP server on localhost (cpp-httplib, Debian's
// libcpp-httplib-dev) showing the render converging. The render job publishes a snapshot of
// its film every second (RenderJobEvents::snapshot, the checkpoints' film copy); the page
// polls /status and shows /image.bmp of the chosen layer, display-referred through OCIO as
// the PNG output is (io/image_output.h, displayBytes). Nothing waits on the page: closing it
// changes nothing, and the render writes its outputs as usual. docs/preview.md.
#include <memory>
#include <string>

#include "render/render_job.h"

namespace tray {

class PreviewServer {
 public:
  /// Listens on 127.0.0.1:`port` (0: a free port) on a thread of its own; throws tray::Error
  /// when it cannot. `title`: the page's (the scene's path).
  PreviewServer(int port, const std::string& title);
  ~PreviewServer();
  PreviewServer(const PreviewServer&) = delete;
  PreviewServer& operator=(const PreviewServer&) = delete;

  int port() const;
  /// Hooks the server to `events` (snapshots every `seconds`, progress, the end) for a job
  /// of `samplesPerPixel` samples per pixel (0: unknown) and its display/view. Keeps the
  /// events' own progress and finished handlers, calling them first.
  void attach(RenderJobEvents& events, const RenderJob& job, double seconds = 1.0);
  /// Publishes the last image (the film the job returned with JobOutputs::keepImage) and its
  /// average samples per pixel.
  void publishFinal(const Film& film, double samples);

  struct State;

 private:
  std::shared_ptr<State> state_;
};

/// The page's HTML (served at /).
std::string previewPage(const std::string& title);

/// An uncompressed 24-bit BMP of `rgb` (row-major, top row first, 3 bytes per pixel): the
/// browser shows it without an image library here.
std::string bmpOf(const unsigned char* rgb, int width, int height);

}  // namespace tray
