// `rcsplat sweep`: what accuracy costs in time. Renders every combination of the cache settings asked for, and path
// tracing at several sample counts (plain and denoised), on one device; judges each against a reference with every
// metric `compare` reports; writes DIR/sweep.csv, each image, and DIR/accuracy_vs_time.png through
// benchmarks/plot_sweep.py when Python and matplotlib are there.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cl/device_info.h"
#include "cl/gpu_context.h"
#include "cli/command_line.h"
#include "kernels/hsh.h"
#include "cli/commands.h"
#include "util/atomic_file.h"
#include "image/comparison.h"
#include "image/image_io.h"
#include "render/render_output.h"
#include "util/error.h"
#include "util/log.h"

namespace rcsplat {
namespace fs = std::filesystem;
namespace {

// One configuration to render: a cache setting or a path-traced sample count.
struct SweepRun {
  std::string name;  // file stem and the CSV's `config`
  RenderSettings settings;
  bool denoise = false;
};

// The Python the helper scripts run under: $RCSPLAT_PYTHON, else the benchmark environment that
// benchmarks/setup_python.sh makes, else python3.
std::string benchmark_python() {
  if (const char* env = std::getenv("RCSPLAT_PYTHON"); env && *env) return env;
  const fs::path venv = fs::path(RCSPLAT_SOURCE_DIR) / "benchmarks" / ".venv" / "bin" / "python";
  return fs::exists(venv) ? venv.string() : "python3";
}

std::string script_path(const std::string& name) {
  return (fs::path(RCSPLAT_SOURCE_DIR) / "benchmarks" / name).string();
}

std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

bool python_has(const std::string& python, const std::string& modules) {
  return std::system(
             (shell_quoted(python) + " -c " + shell_quoted("import " + modules) + " > /dev/null 2>&1").c_str()) == 0;
}

std::string float_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::vector<SweepRun> plan_runs(const SweepOptions& o, const RenderSettings& base, bool denoise) {
  std::vector<SweepRun> runs;
  std::vector<unsigned> orders = o.hsh_orders.empty() ? std::vector<unsigned>{0} : o.hsh_orders;
  for (float a : o.accuracies)
    for (const std::string& hemisphere : o.hemispheres)
      for (unsigned order : orders) {
        SweepRun r{"cache_a" + float_text(a) + "_" + hemisphere + (order ? "_hsh" + std::to_string(order) : ""), base};
        r.settings.gi = GiMethod::splat;
        r.settings.cache.accuracy = a;
        parse_hemisphere(hemisphere, r.settings.cache);  // checks the whole cache setting, --accuracy too
        r.settings.hsh_order = order;
        runs.push_back(r);
      }
  for (unsigned spp : o.path_samples) {
    SweepRun r{"path_" + std::to_string(spp) + "spp", base};
    r.settings.gi = GiMethod::path;
    r.settings.path.samples = spp;
    r.settings.path.stratified = true;
    runs.push_back(r);
    if (denoise) {
      r.name += "_denoised";
      r.denoise = true;
      runs.push_back(r);
    }
  }
  return runs;
}

// The CSV's metric columns for one layer of a comparison.
const char* const kMetricColumns[] = {"rel_mse", "rel_mse_less_noise", "rmse", "mae", "block_rel_mse",
                                      "block_rel_mse_less_noise", "flip"};

std::string metric_cells(const ImageComparison& c, const std::string& layer) {
  const LayerComparison* l = c.find(layer);
  if (!l) return ",,,,,,";
  auto cell = [](std::optional<double> v) { return v ? float_text(*v) : std::string(); };
  return cell(l->pixel.rel_mse) + "," + cell(l->rel_mse_less_reference_noise()) + "," + cell(l->pixel.rmse) + "," +
         cell(l->pixel.mae) + "," + cell(l->block_rel_mse) + "," + cell(l->block_rel_mse_less_reference_noise()) + "," +
         cell(l->mean_flip);
}

}  // namespace

int run_sweep(const SweepOptions& o) {
  set_progress_lines(o.progress_lines);
  if (o.output_dir.empty()) throw Error("sweep: give an output folder with -o DIR");
  if (o.accuracies.empty() && o.path_samples.empty())
    throw Error("sweep: nothing to render (no --accuracy, no --path-spp)");
  for (unsigned spp : o.path_samples)
    if (spp == 0) throw Error("--path-spp: sample counts must be positive");
  // The frame and the bounces are the reference's, so that every run shows what the reference shows.
  int ref_width = 0, ref_height = 0;
  read_exr_rgb(o.reference_path, ref_width, ref_height);
  const ExrAttributes reference_attributes = read_exr_attributes(o.reference_path);
  unsigned bounces = o.bounces;
  if (!bounces) {
    auto it = reference_attributes.find("rcsplat:bounces");
    bounces = it == reference_attributes.end() ? 0u : unsigned(std::atoi(it->second.c_str()));
  }

  RenderSettings base;
  base.width = ref_width;
  base.height = ref_height;
  base.camera = o.camera;
  base.light_samples = o.light_samples;
  base.pixel_samples = o.pixel_samples;
  base.bounces = bounces;  // 0 (a reference from elsewhere): chosen from the scene, as render does

  const std::string python = benchmark_python();
  bool denoise = o.denoise == "on";
  if (o.denoise == "auto") {
    denoise = !o.path_samples.empty() && python_has(python, "pyoidn, OpenEXR, numpy");
    if (!o.path_samples.empty() && !denoise)
      log_warning("sweep: no denoised path tracing: " + python + " lacks pyoidn, OpenEXR or numpy "
                  "(benchmarks/setup_python.sh makes an environment that has them)");
  }
  const std::vector<SweepRun> runs = plan_runs(o, base, denoise);

  fs::create_directories(o.output_dir);
  const std::string csv_path = (fs::path(o.output_dir) / "sweep.csv").string();
  Scene scene = load_scene(o.scene_path, o.camera, {}, o.environment, o.limits);
  DeviceInfo device = select_device(o.device);
  log_info("sweep: " + std::to_string(runs.size()) + " renders of " + scene.source + " at " +
           std::to_string(ref_width) + "x" + std::to_string(ref_height) + " on " + device.name);
  GpuContext gpu(device);
  gpu.set_memory_budget(o.limits.device_memory_bytes);

  std::ostringstream csv;
  csv << "method,config,accuracy,hemisphere,hsh_order,path_spp,denoised,seconds,kernel_build_s,gbuffer_s,direct_s,"
         "records_s,placement_s,splat_s,resolve_s,photon_map_s,light_guide_s,glossy_s,radiance_s,path_s,denoise_s,"
         "records,record_rays,path_rays,device_peak_bytes,bounces,pixel_samples";
  for (const char* layer : {"full", "indirect"})
    for (const char* m : kMetricColumns) csv << "," << layer << "_" << m;
  csv << "\n";

  std::printf("%-34s %9s %12s %12s %8s\n", "config", "seconds", "ind relMSE", "ind block", "FLIP");
  const ProgressHidden hidden;  // a line a run instead of each pass's progress (and of its Progress lines)
  const bool was_quiet = is_quiet();
  // A small frame of each method first: drivers that compile at first launch (PoCL) would otherwise charge the first
  // timed run of each method for it.
  set_quiet(true);
  for (GiMethod method : {GiMethod::splat, GiMethod::path}) {
    for (const SweepRun& run : runs)
      if (run.settings.gi == method && !run.denoise) {
        RenderSettings warm = run.settings;
        warm.width = std::min(ref_width, 64);
        warm.height = std::min(ref_height, 48);
        render(gpu, scene, warm);
        break;
      }
  }
  set_quiet(was_quiet);
  RenderedImage last_path;  // the plain run a denoised run starts from
  std::string last_path_exr;
  for (size_t i = 0; i < runs.size(); ++i) {
    const SweepRun& run = runs[i];
    // Progress on stderr, one line a run; the renders themselves are quiet so that it stays readable.
    std::fprintf(stderr, "sweep [%zu/%zu] %s\n", i + 1, runs.size(), run.name.c_str());
    report_progress(double(i) / double(runs.size()));
    const std::string exr = (fs::path(o.output_dir) / (run.name + ".exr")).string();
    RenderedImage image;
    double denoise_s = 0.0;
    if (run.denoise) {
      // pyoidn denoises the plain run's image and indirect layer with its albedo and normal layers; the time is
      // what the script measured around the denoiser itself.
      image = last_path;
      const std::string report = (fs::path(o.output_dir) / (run.name + ".json")).string();
      const std::string command = shell_quoted(python) + " " + shell_quoted(script_path("denoise.py")) + " " +
                                  shell_quoted(last_path_exr) + " " + shell_quoted(exr) + " --json " +
                                  shell_quoted(report) + " > /dev/null";
      if (std::system(command.c_str()) != 0) throw Error("sweep: denoising failed: " + command);
      std::ifstream in(report);
      denoise_s = nlohmann::json::parse(in).at("seconds").get<double>();
    } else {
      set_quiet(true);
      image = render(gpu, scene, run.settings);
      set_quiet(was_quiet);
      write_render(exr, image, 0.0f, render_attributes(scene, image, run.settings));
      if (run.settings.gi == GiMethod::path) {
        last_path = image;
        last_path_exr = exr;
      }
    }
    set_quiet(true);
    const ImageComparison c = compare_exr_files(exr, o.reference_path, o.block, o.exposure);
    set_quiet(was_quiet);
    const RenderStats& s = image.stats;
    const double seconds = s.seconds_without_builds() + denoise_s;
    const bool cache = run.settings.gi == GiMethod::splat;
    csv << (cache         ? "cache"
            : run.denoise ? "path+denoise"
                          : "path")
        << "," << run.name << "," << (cache ? float_text(run.settings.cache.accuracy) : "") << ","
        << (cache
                ? std::to_string(run.settings.cache.theta_strata) + "x" + std::to_string(run.settings.cache.phi_strata)
                : "")
        << "," << (cache ? std::to_string(s.radiance.order) : "") << ","
        << (cache ? "" : std::to_string(run.settings.path.samples)) << "," << (run.denoise ? 1 : 0) << "," << seconds
        << "," << s.program_s << "," << s.primary.gbuffer_s << "," << s.primary.direct_s << ","
        << s.irradiance.records_s << "," << s.irradiance.placement_s << "," << s.irradiance.splat_s << ","
        << s.irradiance.resolve_s << "," << s.photon_map.seconds << "," << s.guide.seconds << "," << s.glossy.seconds
        << "," << s.radiance.seconds() << ","
        << s.path.seconds << "," << denoise_s << "," << s.irradiance.records << "," << s.irradiance.rays << ","
        << s.path.rays << "," << s.device_memory.peak_bytes << "," << s.bounces.count << "," << s.primary.pixel_samples;
    for (const char* layer : {"full", "indirect"}) csv << "," << metric_cells(c, layer);
    csv << "\n";
    const LayerComparison* ind = c.find("indirect") ? c.find("indirect") : c.find("full");
    std::printf("%-34s %9.3f %12.4e %12.4e %8.4f\n", run.name.c_str(), seconds, ind->pixel.rel_mse,
                ind->block_rel_mse.value_or(0.0), ind->mean_flip);
    std::fflush(stdout);
    write_text_file(csv_path, csv.str());  // after every run, so an interrupted sweep keeps what it measured
  }
  std::printf("wrote        %s\n", csv_path.c_str());

  if (o.plot) {
    const std::string png = (fs::path(o.output_dir) / "accuracy_vs_time.png").string();
    if (!python_has(python, "matplotlib")) {
      log_warning("sweep: no plot: " + python + " lacks matplotlib (benchmarks/setup_python.sh makes an environment "
                  "that has it); plot later with: python3 benchmarks/plot_sweep.py " + csv_path);
    } else if (std::system((shell_quoted(python) + " " + shell_quoted(script_path("plot_sweep.py")) + " " +
                            shell_quoted(csv_path) + " -o " + shell_quoted(png) + " > /dev/null")
                               .c_str()) != 0) {
      log_warning("sweep: benchmarks/plot_sweep.py failed; the CSV is complete");
    } else {
      std::printf("wrote        %s\n", png.c_str());
    }
  }
  report_progress(1.0);
  return 0;
}

Command add_sweep_command(CLI::App& app, const HelpGroups&) {
  struct State {
    SweepOptions options;
    EnvironmentFlags environment;
  };
  auto s = std::make_shared<State>();
  SweepOptions& o = s->options;
  const SweepOptions defaults;
  auto listed = [](const auto& values) {
    std::string text;
    for (const auto& v : values) {
      std::ostringstream one;
      one << v;
      text += (text.empty() ? "" : ",") + one.str();
    }
    return text;
  };
  CLI::App* cmd = app.add_subcommand(
      "sweep", "What accuracy costs in time: cache settings and path tracing against a reference, as a CSV and a plot");
  cmd->add_option("scene", o.scene_path, "glTF 2.0 scene (default: the built-in Cornell box)");
  cmd->add_option("--reference", o.reference_path,
                  "Converged reference (.exr from `rcsplat reference`): the frame size and bounces follow it")
      ->required();
  cmd->add_option("-o,--output", o.output_dir, "Folder for sweep.csv, accuracy_vs_time.png and the images")
      ->required();
  cmd->add_option("--device", o.device, "OpenCL device: index or name substring");
  cmd->add_option("--accuracy", o.accuracies,
                  "Cache accuracies (default " + listed(defaults.accuracies) + "; none: --accuracy \"\")")
      ->delimiter(',')
      ->expected(0, 64);
  cmd->add_option("--hemisphere", o.hemispheres, "Rays per record, MxN each (default " + listed(defaults.hemispheres) + ")")
      ->delimiter(',')
      ->expected(0, 64);
  cmd->add_option("--hsh-order", o.hsh_orders, "HSH orders of radiance-cached lobes (default: chosen)")
      ->delimiter(',')
      ->expected(0, 64)
      ->check(CLI::Range(1u, unsigned(HSH_MAX_ORDER)));
  cmd->add_option("--path-spp", o.path_samples,
                  "Stratified path tracing at these samples per pixel (default " + listed(defaults.path_samples) +
                      "; none: --path-spp \"\")")
      ->delimiter(',')
      ->expected(0, 64);
  cmd->add_option("--denoise", o.denoise,
                  "Path tracing plus Intel Open Image Denoise (pyoidn, benchmarks/denoise.py) beside plain: auto "
                  "(when the benchmark Python has it; default), on, off")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  cmd->add_flag("!--no-plot", o.plot, "Do not draw accuracy_vs_time.png");
  cmd->add_flag("--progress-lines", o.progress_lines,
                "Also print the sweep's progress as lines \"Progress: NN%\" on stdout (a run each), as render-farm "
                "managers read it");
  cmd->add_option("--light-samples", o.light_samples,
                  "Light samples per pixel (default " + std::to_string(defaults.light_samples) + ")")
      ->check(CLI::Range(0u, kMaxLightSamples));
  cmd->add_option("--pixel-samples", o.pixel_samples, "Primary samples per pixel (default: as render)")
      ->check(CLI::Range(1u, 64u));
  cmd->add_option("--bounces", o.bounces, "Indirect bounces (default: the reference's)")
      ->check(CLI::Range(1u, unsigned(kMaxBounces)));
  cmd->add_option("--camera", o.camera, "Index of the scene camera to use")->check(CLI::NonNegativeNumber);
  cmd->add_option("--block", o.block, "Block size of block relMSE (default " + std::to_string(defaults.block) + ")")
      ->check(CLI::Range(1, 4096));
  s->environment.add(cmd, o.environment);
  add_scene_limit_options(cmd, o.limits, true);
  return {cmd, [s] {
            s->environment.apply(s->options.environment);
            return run_sweep(s->options);
          }};
}

}  // namespace rcsplat
