// Job bookkeeping shared by every study: job list, shards, resume, merge and provenance.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>

#include "flight_settings.hpp"
#include "results_store.hpp"
#include "study.hpp"
#include "world.hpp"
#include "trn/build_info.hpp"
#include "trn/error.hpp"
#include "trn/parse_number.hpp"
#include "trn/experiments/experiment.hpp"
#include "trn/io/input_file.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/outside_text.hpp"
#include "trn/io/output_folder.hpp"
#include "trn/io/provenance.hpp"
#include "trn/registry.hpp"

namespace trn::experiments {
namespace fs = std::filesystem;

std::vector<std::string> study_names() { return {"metrics", "heading", "sampling", "conversion", "robustness", "odometry", "odometry-wind",
                                                       "odometry-visual", "odometry-long", "template-width"}; }

namespace {

std::unique_ptr<Study> make_study(const std::string& name, const std::string& shared_data) {
    if (name == "metrics") return make_metrics_study(orthophoto_path(shared_data));
    if (name == "heading") return make_heading_study(orthophoto_path(shared_data));
    if (name == "sampling") return make_sampling_study();
    if (name == "conversion") return make_conversion_study();
    if (name == "robustness") return make_robustness_study();
    if (name == "odometry") return make_odometry_study(false);
    if (name == "odometry-wind") return make_odometry_study(true);
    if (name == "odometry-visual") return make_odometry_study(false, true);
    if (name == "odometry-long") return make_long_odometry_study();
    if (name == "template-width") return make_template_width_study();
    std::string names;
    for (const auto& n : study_names()) names += " " + n;
    throw Error("experiment: unknown study '" + name + "' (one of:" + names + ")");
}

}  // namespace

Shard parse_shard(const std::string& text) {
    const std::size_t slash = text.find('/');
    const auto i = parse_whole_number(std::string_view(text).substr(0, slash));
    const auto n = slash == std::string::npos ? std::nullopt : parse_whole_number(std::string_view(text).substr(slash + 1));
    if (!i || !n || *n == 0 || *i == 0 || *i > *n || *n > kMaxShards)
        throw Error("experiment: `shard` '" + text + "' must be i/n with 1 <= i <= n <= " + std::to_string(kMaxShards));
    return {static_cast<std::size_t>(*i - 1), static_cast<std::size_t>(*n)};
}

namespace {

Json read_json(const std::string& path) {
    const std::string text = io::read_input_file(path, io::kMaxJsonFileBytes, "a job file");
    io::check_json_depth(text, path);
    try {
        return Json::parse(text);
    } catch (const std::exception& e) {
        throw Error(path + ": not valid JSON (" + io::quote_input(e.what(), 200) + "); delete it to re-run that job");
    }
}

// A job file is either complete or absent (a run killed while writing leaves the old state).
void write_json(const std::string& path, const Json& j) { io::write_file_atomic(path, io::json_text(j, 1)); }

void progress_bar(std::size_t done, std::size_t total, const std::string& what) {
    const int width = 30, filled = total ? static_cast<int>(width * done / total) : width;
    std::fprintf(stderr, "\r[%s%s] %zu/%zu jobs %-40.40s", std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(),
                 done, total, what.c_str());
    if (done == total) std::fputc('\n', stderr);
}

// One word for a POSIX shell, whatever it holds: as it is when plain, else '...' with each ' as '\''.
std::string shell_word(const std::string& text) {
    const bool plain = !text.empty() && text.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./:=+,@%-") ==
                                            std::string::npos;
    if (plain) return text;
    std::string quoted = "'";
    for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

std::string command_prefix(const ExperimentOptions& o, const std::string& out) {
    std::string radius;
    if (!std::isnan(o.init_radius_m)) {
        char text[48];  // " --init-radius-m " and up to 24 characters of %.17g: 32 cut 99999.123456789012 short
        std::snprintf(text, sizeof text, " --init-radius-m %.17g", o.init_radius_m);  // reads back as the same double
        radius = text;
    }
    std::string profile;
    if (o.profile != "ours") profile += " --profile " + shell_word(o.profile);
    if (!o.lock_monitor.empty()) profile += " --lock-monitor " + shell_word(o.lock_monitor);
    if (o.max_particles) profile += " --max-particles " + std::to_string(o.max_particles);
    if (!std::isnan(o.kld_upper_quantile)) {
        char text[48];
        std::snprintf(text, sizeof text, " --kld-upper-quantile %.17g", o.kld_upper_quantile);
        profile += text;
    }
    if (!o.results.empty()) profile += " --results " + shell_word(o.results);
    if (o.resume) profile += " --resume";
    return "trnkit experiment " + o.study + (o.quick ? " --quick" : "") + " --seed " + std::to_string(o.seed) + radius + profile + " --backend " +
           shell_word(o.backend) + " --out " + shell_word(out);
}

}  // namespace

namespace {

// --backend is checked for form before anything (--list-jobs and --prepare too, whose output
// dispatchers pass on): "fastest" or a family this build has, optionally ":" and an index or a
// name text. Whether the device exists is left to the job runs (a login node may have no GPU).
void check_backend_spec(const std::string& spec) {
    if (spec == "fastest") return;
    const std::size_t colon = spec.find(':');
    const std::string family = spec.substr(0, colon);
    std::string known;
    bool found = false;
    for (const BackendFamily& f : default_registry().families()) known += (known.empty() ? "" : ", ") + f.name, found |= f.name == family;
    if (!found) throw Error("experiment: `backend` '" + io::quote_input(spec) + "': unknown backend (one of fastest, " + known + ")");
    if (colon == std::string::npos) return;
    const std::string selector = spec.substr(colon + 1);
    if (selector.empty() || selector.size() > 64 ||
        selector.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789 ._-") != std::string::npos)
        throw Error("experiment: `backend` '" + io::quote_input(spec) + "': after '" + family +
                    ":' comes a device index or name text (letters, digits, space . _ -)");
}

// A study's whole configuration under these options: what its jobs share and what a stored line must match.
Json full_configuration(const Study& study, const ExperimentOptions& o) {
    Json config = study.config(o.quick);
    config["study"] = study.name();
    config["quick"] = o.quick;
    config["seed"] = o.seed;
    config["backend"] = o.backend;
    // The filter's profile and lock monitor are part of the configuration (jobs of another are refused, not mixed).
    const filter::Profile profile = [&] {
        try {
            return filter::parse_profile(o.profile);
        } catch (const Error&) {
            throw Error("experiment: `profile` '" + io::quote_input(o.profile) + "': unknown; expected ours or dissertation");
        }
    }();
    config["profile"] = filter::to_string(profile);
    if (!o.lock_monitor.empty() && o.lock_monitor != "on" && o.lock_monitor != "off")
        throw Error("experiment: `lock_monitor` '" + io::quote_input(o.lock_monitor) + "': expected on or off");
    if (config.contains("filter")) {  // the studies that run the filter
        if (profile == filter::Profile::Dissertation) config["filter"] = kDissertationFilter;
        config["lock_monitor"] = o.lock_monitor.empty() ? filter::profile_config(profile).lock.enabled : o.lock_monitor == "on";
    } else if (!o.lock_monitor.empty()) {
        throw Error("experiment " + o.study + ": `lock_monitor`: this study runs no particle filter (it scores poses only)");
    }
    // Part of the configuration when given (absent otherwise, so the stores of the profiles' own
    // settings keep their hashes): the flight studies' KLD maximum and upper quantile.
    if (o.max_particles || !std::isnan(o.kld_upper_quantile)) {
        if (!config.contains("init_radius_m"))
            throw Error("experiment " + o.study + ": `max_particles`, `kld_upper_quantile`: only the flight studies (conversion, robustness, odometry*)");
        if (o.max_particles) {
            if (o.max_particles < 100 || o.max_particles > 1000000)
                throw Error("experiment: `max_particles` " + std::to_string(o.max_particles) + " must be in [100, 1000000]");
            config["max_particles"] = o.max_particles;
        }
        if (!std::isnan(o.kld_upper_quantile)) {
            if (!(o.kld_upper_quantile > 0 && o.kld_upper_quantile < 1))
                throw Error("experiment: `kld_upper_quantile` " + std::to_string(o.kld_upper_quantile) + " must be in (0, 1)");
            config["kld_upper_quantile"] = o.kld_upper_quantile;
        }
    }
    if (!std::isnan(o.init_radius_m)) {  // part of the configuration: jobs of another radius are refused, not mixed
        if (!config.contains("init_radius_m"))
            throw Error("experiment " + o.study + ": `init_radius_m`: this study has no start radius (only conversion, robustness, odometry, odometry-wind)");
        if (!(o.init_radius_m > 0 && o.init_radius_m <= 1e5))
            throw Error("experiment: `init_radius_m` " + std::to_string(o.init_radius_m) + " must be in (0, 100000]");
        config["init_radius_m"] = o.init_radius_m;
    }
    return config;
}

}  // namespace

namespace {

// A stored job's output, its params checked against the job's own: the merge reads them by type.
Json checked_stored_output(const ResultsStore& store, const Json& job) {
    const std::string id = job.at("id").get<std::string>();
    Json out = store.output(id);
    // Key order differs (the store keeps the id apart): compare unordered.
    if (nlohmann::json::parse(io::json_line(out.at("params"))) != nlohmann::json::parse(io::json_line(job)))
        throw Error(store.where(id) + ": field params is " + io::quote_input(io::json_line(out.at("params")), 200) + ", but job " + io::quote_input(id) +
                    " of this study is " + io::quote_input(io::json_line(job), 200));
    out["params"] = job;
    return out;
}

}  // namespace

std::size_t run_experiment(const ExperimentOptions& o) {
    check_backend_spec(o.backend);
    const auto study = make_study(o.study, o.shared_data);
    const Json config = full_configuration(*study, o);
    const filter::Profile profile = filter::parse_profile(config.at("profile").get<std::string>());
    const std::vector<Json> jobs = study->jobs(config);
    std::set<std::string> ids;
    for (const Json& j : jobs) {
        const std::string id = j.at("id").get<std::string>();
        // Ids travel through dispatchers as one word and in comma lists (--job a,b): a study bug otherwise.
        if (id.empty() || id.find_first_of(", \t\n") != std::string::npos) throw Error("experiment: job id " + io::json_line(j.at("id")) + " has a comma or blank");
        if (!ids.insert(id).second) throw Error("experiment: duplicate job id " + io::json_line(j.at("id")));
    }

    const std::string out = o.out.empty() ? "experiments/" + o.study + (profile == filter::Profile::Dissertation ? "-dissertation" : "") +
                                                (o.quick ? "-quick" : "")
                                          : o.out;
    // The results store: read always (appends skip the jobs it holds), used to skip and merge with --resume.
    ResultsStore store(o.results == "none" ? std::string() : o.results.empty() ? default_results_path(o.study, config["profile"], o.quick) : o.results,
                       config);
    if (o.resume && !store.enabled()) throw Error("experiment: `resume` needs the results store (not `results` none)");
    const std::string store_note = store.load();
    if (o.resume && !store_note.empty() && !o.list_jobs) std::cerr << "experiment " << o.study << ": note: " << store_note << "\n";
    // The store of the study whose flights these are (robustness: conversion's), read with --resume
    // when both use their default stores: a flight either has made counts for both.
    const std::string lender = study->flights_shared_with();
    ResultsStore shared(o.resume && o.results.empty() && !lender.empty() ? default_results_path(lender, config["profile"], o.quick) : std::string(),
                        lender.empty() ? Json() : full_configuration(*make_study(lender, o.shared_data), o));
    if (shared.enabled()) shared.load();  // its lines of other configurations are that study's business
    auto stored = [&](const std::string& id) { return o.resume && (store.has(id) || shared.has(id)); };
    if (o.list_jobs && o.list_ids_only) {  // for scripts: each line is one --job argument, never shell text
        std::size_t listed = 0;
        for (const Json& j : jobs) {
            const std::string id = j.at("id").get<std::string>();
            if (stored(id)) continue;
            std::cout << id;
            if (o.list_keys) {
                const std::string key = study->inputs_key(j);
                if (key.find_first_of(" \t\n") != std::string::npos) throw Error("experiment: inputs key '" + key + "' of " + id + " has a blank");
                std::cout << " " << (key.empty() ? id : key);
            }
            std::cout << "\n";
            ++listed;
        }
        return listed;
    }
    if (o.list_jobs) {
        for (const Json& j : jobs) std::cout << command_prefix(o, out) << " --job " << shell_word(j.at("id").get<std::string>()) << " --no-merge\n";
        std::cout << command_prefix(o, out) << " --merge\n";
        return jobs.size();
    }
    for (const std::string& id : o.jobs)
        if (!ids.count(id)) throw Error("experiment: `job` " + io::quote_input(id) + ": no such job in " + o.study + " (see `list_jobs`)");
    const std::set<std::string> chosen(o.jobs.begin(), o.jobs.end());
    const Shard shard = parse_shard(o.shard);  // checked before the output folder is touched

    // Every option checked: now the folder (this study's earlier output resumes; others are refused).
    io::open_output_folder(out, "experiment " + o.study, o.force);
    const std::string jobs_dir = out + "/jobs";
    std::error_code ec;
    fs::create_directories(jobs_dir, ec);
    if (ec) throw Error(jobs_dir + ": cannot create folder (" + ec.message() + ")");
    auto job_path = [&](const Json& j) { return jobs_dir + "/" + j.at("id").get<std::string>() + ".json"; };
    // A finished job is reused only when it was made with exactly this configuration.
    auto in_store = [&](const Json& j) { return stored(j.at("id").get<std::string>()); };
    auto finished = [&](const Json& j) {
        if (in_store(j)) return true;
        const std::string path = job_path(j);
        if (!fs::exists(path)) return false;
        const Json done = read_json(path);
        if (done.at("config") != config)
            throw Error("experiment: " + path + " was made with another configuration (" + io::json_line(done.at("config")) + ", asked for " +
                        io::json_line(config) + "); use another `out` or delete it");
        return true;
    };

    if (o.prepare_only) {  // folder ready, every finished job checked against this configuration
        std::size_t missing = 0;
        for (const Json& j : jobs) missing += finished(j) ? 0 : 1;
        std::cerr << "experiment " << o.study << ": " << jobs.size() - missing << " of " << jobs.size() << " jobs finished in " << out << "\n";
        return missing;
    }
    if (!o.merge_only) {
        std::vector<const Json*> todo;
        for (std::size_t i = shard.index; i < jobs.size(); i += shard.count)
            if ((chosen.empty() || chosen.count(jobs[i].at("id").get<std::string>())) && !finished(jobs[i])) todo.push_back(&jobs[i]);
        if (!todo.empty()) {
            std::unique_ptr<Backend> backend = default_registry().create(o.backend, o.backend_options);
            for (std::size_t k = 0; k < todo.size(); ++k) {
                const Json& params = *todo[k];
                if (o.progress) progress_bar(k, todo.size(), params.at("id").get<std::string>());
                const std::string folder = jobs_dir + "/" + params.at("id").get<std::string>();
                JobContext context{*backend, o.seed, o.quick, folder, !o.no_plots};
                const auto t0 = std::chrono::steady_clock::now();
                Json result = study->run_job(config, params, context);
                const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                Json job{{"config", config}, {"params", params}, {"result", result}, {"wall_s", wall}, {"backend_device", backend->info().device}};
                io::add_provenance(job);
                write_json(job_path(params), job);
                if (!store.has(params.at("id").get<std::string>()) && !shared.has(params.at("id").get<std::string>()))
                    store.append(params, result, wall, backend->info().device, std::string(build_info().git_commit));
            }
            if (o.progress) progress_bar(todo.size(), todo.size(), "done");
        }
    }
    if (o.no_merge) return 0;

    std::vector<Json> outputs;
    std::size_t missing = 0, from_store = 0, from_shared = 0;
    double wall_s = 0;
    std::set<std::string> devices;
    for (const Json& j : jobs) {
        if (!finished(j)) {
            ++missing;
            continue;
        }
        const std::string id = j.at("id").get<std::string>();
        if (o.resume && store.has(id)) {
            outputs.push_back(checked_stored_output(store, j));
            ++from_store;
        } else if (o.resume && shared.has(id)) {
            outputs.push_back(checked_stored_output(shared, j));
            ++from_shared;
        } else {
            outputs.push_back(read_json(job_path(j)));
        }
        wall_s += outputs.back().value("wall_s", 0.0);
        devices.insert(outputs.back().value("backend_device", std::string("?")));
    }
    if (missing && (!o.partial || outputs.empty())) {
        std::cerr << "experiment " << o.study << ": " << missing << " of " << jobs.size() << " jobs not finished; tables not built\n";
        return missing;
    }
    MergeContext mc{out, config, !o.no_plots};
    std::string markdown;
    try {
        markdown = study->merge(outputs, mc);
    } catch (const nlohmann::json::exception& e) {  // a field the store's checks cannot know of: still one line, exit 1
        throw Error("experiment " + o.study + ": the job outputs cannot be merged: a field is missing or of another type (" + e.what() +
                    "); they came from " + (from_store ? store.path() + ", " : std::string()) + (from_shared ? shared.path() + ", " : std::string()) +
                    "job files in " + jobs_dir);
    }
    if (missing)
        markdown = "**PARTIAL RUN: " + std::to_string(outputs.size()) + " of " + std::to_string(jobs.size()) +
                   " jobs finished; cells are means over the finished jobs only.**\n\n" + markdown;
    {
        std::string head = "Profile: " + config["profile"].get<std::string>();
        if (config.contains("lock_monitor")) head += std::string(", lock monitor ") + (config["lock_monitor"].get<bool>() ? "on" : "off");
        if (config.contains("max_particles")) head += ", at most " + std::to_string(config["max_particles"].get<std::size_t>()) + " particles";
        if (config.contains("kld_upper_quantile")) {
            char q[32];
            std::snprintf(q, sizeof q, "%g", config["kld_upper_quantile"].get<double>());
            head += std::string(", KLD upper quantile ") + q;
        }
        head += "; " + std::to_string(outputs.size()) + " of " + std::to_string(jobs.size()) + " jobs";
        if (from_store) head += " (" + std::to_string(from_store) + " from the results store " + store.path() + ", configuration " + store.hash() + ")";
        if (from_shared)
            head += " (" + std::to_string(from_shared) + " flights of " + lender + " from " + shared.path() + ", configuration " + shared.hash() + ")";
        markdown = head + ".\n\n" + markdown;
    }
    io::write_file_atomic(out + "/results.md", markdown);
    Json prov{{"study", o.study}, {"profile", config["profile"]}, {"seed", o.seed}, {"backend", o.backend},
              {"results_store", store.path()}, {"config_hash", store.hash()}, {"jobs_from_store", from_store}, {"shared_store", shared.path()}, {"jobs_from_shared_store", from_shared},
              {"backend_devices", devices}, {"jobs", jobs.size()}, {"jobs_merged", outputs.size()}, {"job_wall_s_total", wall_s}, {"config", config}};
    io::add_provenance(prov);
    write_json(out + "/provenance.json", prov);
    std::cout << markdown << "\ntables, plots and provenance.json in " << out << " (" << jobs.size() << " jobs, " << wall_s
              << " s of job time)\n";
    return 0;
}

}  // namespace trn::experiments
