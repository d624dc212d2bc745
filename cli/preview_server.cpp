#include "cli/preview_server.h"

#include <httplib.h>

#include <chrono>
#include <cstdio>
#include <mutex>
#include <thread>

#include "core/error.h"
#include "io/image_output.h"

namespace tray {

struct PreviewServer::State {
  httplib::Server server;
  std::thread thread;
  int port = 0;
  std::string title, display, view;
  std::mutex mutex;  // guards what follows
  std::shared_ptr<const Film> film;
  uint64_t version = 0;
  double fraction = 0, samples = 0, elapsed = 0;
  bool done = false;
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
};

namespace {

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out + "\"";
}

std::string statusJson(PreviewServer::State& st) {
  std::lock_guard lock(st.mutex);
  const double eta =
      st.fraction > 0 && !st.done ? st.elapsed * (1 - st.fraction) / st.fraction : 0;
  std::string layers;
  if (st.film)
    for (const FilmLayer& l : st.film->layers()) {  // appended piecewise: GCC 12's -Wrestrict
      if (!layers.empty()) layers += ',';
      layers += jsonString(l.name.empty() ? "beauty" : l.name);
    }
  char numbers[256];
  std::snprintf(numbers, sizeof numbers,
                "\"version\":%llu,\"fraction\":%.6f,\"samples\":%.3f,\"elapsed\":%.3f,"
                "\"eta\":%.3f,\"done\":%s,",
                (unsigned long long)st.version, st.fraction, st.samples, st.elapsed, eta,
                st.done ? "true" : "false");
  std::string out = "{";
  out += numbers;
  out += "\"title\":" + jsonString(st.title);
  out += ",\"layers\":[" + layers + "]}";
  return out;
}

/// The average samples per pixel in `state`: each pixel's count in a render in passes, else
/// `spp` for each pixel done.
double samplesOf(const RenderState& state, int spp) {
  const size_t n = state.done.size();
  if (n == 0) return 0;
  if (!state.progress.empty()) {
    double sum = 0;
    for (const PixelProgress& p : state.progress) sum += p.count;
    return sum / double(n);
  }
  return double(state.pixelsDone()) * spp / double(n);
}

void publish(PreviewServer::State& st, std::shared_ptr<const Film> film, double samples) {
  std::lock_guard lock(st.mutex);
  st.film = std::move(film);
  st.samples = samples;
  st.elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - st.started).count();
  ++st.version;
}

void serveImage(PreviewServer::State& st, const httplib::Request& req, httplib::Response& res) {
  std::shared_ptr<const Film> film;
  {
    std::lock_guard lock(st.mutex);
    film = st.film;
  }
  if (!film) {
    res.status = 404;
    return;
  }
  const std::string name = req.has_param("layer") ? req.get_param_value("layer") : "beauty";
  const int layer = film->findLayer(name == "beauty" ? "" : name);
  if (layer < 0) {
    res.status = 404;
    return;
  }
  // Encoded here, on the server's thread, only when the page asks: the render pays for the
  // film copy alone.
  const std::vector<unsigned char> rgb = displayBytes(*film, layer, st.display, st.view);
  res.set_content(bmpOf(rgb.data(), film->width(), film->height()), "image/bmp");
  res.set_header("Cache-Control", "no-store");
}

}  // namespace

std::string bmpOf(const unsigned char* rgb, int width, int height) {
  const int rowBytes = (width * 3 + 3) & ~3;
  const uint32_t dataBytes = uint32_t(rowBytes) * uint32_t(height), fileBytes = 54 + dataBytes;
  std::string out(fileBytes, '\0');
  auto put = [&out](size_t at, uint32_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out[at + i] = char((v >> (8 * i)) & 0xff);
  };
  out[0] = 'B', out[1] = 'M';
  put(2, fileBytes, 4), put(10, 54, 4), put(14, 40, 4);
  put(18, uint32_t(width), 4), put(22, uint32_t(-height), 4);  // negative: top row first
  put(26, 1, 2), put(28, 24, 2), put(34, dataBytes, 4);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const unsigned char* p = rgb + (size_t(y) * width + x) * 3;
      char* q = &out[54 + size_t(y) * rowBytes + size_t(x) * 3];
      q[0] = char(p[2]), q[1] = char(p[1]), q[2] = char(p[0]);  // BGR
    }
  return out;
}

PreviewServer::PreviewServer(int port, const std::string& title)
    : state_(std::make_shared<State>()) {
  State& st = *state_;
  st.title = title;
  st.server.Get("/", [title](const httplib::Request&, httplib::Response& res) {
    res.set_content(previewPage(title), "text/html; charset=utf-8");
  });
  st.server.Get("/status", [&st](const httplib::Request&, httplib::Response& res) {
    res.set_content(statusJson(st), "application/json");
    res.set_header("Cache-Control", "no-store");
  });
  st.server.Get("/image.bmp", [&st](const httplib::Request& req, httplib::Response& res) {
    serveImage(st, req, res);
  });
  st.port = port == 0 ? st.server.bind_to_any_port("127.0.0.1")
                      : (st.server.bind_to_port("127.0.0.1", port) ? port : -1);
  if (st.port < 0)
    throw Error("--preview " + std::to_string(port) +
                ": cannot listen on 127.0.0.1 at that port (in use?)");
  st.thread = std::thread([&st] { st.server.listen_after_bind(); });
}

PreviewServer::~PreviewServer() {
  state_->server.stop();
  if (state_->thread.joinable()) state_->thread.join();
}

int PreviewServer::port() const { return state_->port; }

void PreviewServer::attach(RenderJobEvents& events, const RenderJob& job, double seconds) {
  state_->display = job.outputs.display, state_->view = job.outputs.view;
  const int spp = job.settings.getInt("spp");
  std::shared_ptr<State> st = state_;
  events.snapshotSeconds = seconds;
  events.snapshot = [st, spp](const Film& film, const RenderState& state) {
    publish(*st, std::make_shared<const Film>(film), samplesOf(state, spp));
  };
  events.started = [st, inner = events.started] {
    if (inner) inner();
    std::lock_guard lock(st->mutex);
    st->started = std::chrono::steady_clock::now();
  };
  events.progress = [st, inner = events.progress](double f) {
    if (inner) inner(f);
    std::lock_guard lock(st->mutex);
    st->fraction = f;
    st->elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - st->started).count();
  };
}

void PreviewServer::publishFinal(const Film& film, double samples) {
  publish(*state_, std::make_shared<const Film>(film), samples);
  std::lock_guard lock(state_->mutex);
  state_->done = true, state_->fraction = 1;
}

std::string previewPage(const std::string& title) {
  std::string escaped;
  for (char c : title) escaped += c == '<' ? std::string("&lt;") : c == '&' ? "&amp;" : std::string(1, c);
  // The page polls /status twice a second and loads a new image when the render published
  // one (its version changed) or the layer changed.
  return R"(<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>TRay preview: )" +
         escaped + R"(</title>
<style>body{background:#222;color:#ddd;font:14px sans-serif;margin:16px}
img{image-rendering:pixelated;max-width:100%;border:1px solid #444}</style></head>
<body><div><b>TRay preview</b>: )" +
         escaped + R"(</div>
<div>layer <select id="layer"></select> <span id="status">waiting for the first image</span></div>
<img id="image" alt="the render so far">
<script>
let shown = -1, shownLayer = "beauty", loads = 0;
const layer = document.getElementById("layer"), image = document.getElementById("image");
layer.onchange = () => { shown = -1; };
image.onload = () => { loads++; document.body.dataset.loads = loads;
                       document.body.dataset.layer = image.dataset.layer; };
function seconds(s) { return s < 60 ? s.toFixed(1) + " s" : (s / 60).toFixed(1) + " min"; }
async function poll() {
  try {
    const st = await (await fetch("/status", {cache: "no-store"})).json();
    if (layer.options.length != st.layers.length) {
      layer.innerHTML = "";
      for (const name of st.layers) layer.add(new Option(name, name));
      layer.value = shownLayer;
    }
    document.getElementById("status").textContent =
      (st.fraction * 100).toFixed(1) + "% done, " + st.samples.toFixed(1) + " samples per pixel, " +
      seconds(st.elapsed) + " elapsed, " + (st.done ? "finished" : seconds(st.eta) + " left");
    document.body.dataset.version = st.version;
    if (st.version > 0 && (st.version != shown || layer.value != shownLayer)) {
      shown = st.version; shownLayer = layer.value || "beauty";
      image.dataset.layer = shownLayer;
      image.src = "/image.bmp?layer=" + encodeURIComponent(shownLayer) + "&v=" + shown;
    }
  } catch (e) { document.getElementById("status").textContent = "render ended"; }
  setTimeout(poll, 500);
}
poll();
</script></body></html>
)";
}

}  // namespace tray
