// fuzz_inputs [--jobs N] [--seed S] CLOTHSIM SEED.prm SEED.msh... SCRATCH_DIR
//
// Fuzz test of the parameter parser and the mesh reader (issue 14). From a fixed random
// seed it makes a few hundred mutants (fuzz_mutations.h) of the parameter seed and of
// each mesh seed, and runs each as
//   clothsim SCRATCH_DIR/mutant-N/mutant.prm --output-dir SCRATCH_DIR/out-N
// (a mesh mutant as mutant.msh beside the unmutated parameter seed; a parameter mutant
// with the first mesh seed as mesh.msh). Each run must exit with 0 (success), 2
// (simulation failed), or 1 (bad input) with exactly one line "clothsim: error: ..." on
// stderr, no output directory and nothing else written; never by a signal, with another
// code, or after more than 20 s (a hang; 200 s in a build with AddressSanitizer). Failing
// mutants stay in SCRATCH_DIR, printed with their mutation, result and stderr; a summary
// by kind and exit code follows. Exits with 1 if any mutant failed. Standalone (POSIX
// fork/exec, no deal.II): builds in seconds.

#include "fuzz_mutations.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#  include <sys/prctl.h>
#endif

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace
{
  using namespace clothsim::fuzz;
  namespace fs = std::filesystem;
  using Clock  = std::chrono::steady_clock;

  // A build with AddressSanitizer (this harness gets clothsim's compiler flags): ASan
  // reserves terabytes of address space for its shadow memory, so the runs get no
  // RLIMIT_AS; its allocator returns null instead for a request above the same 4 GB (as
  // malloc does under the limit), and a run may take ten times longer before it counts
  // as a hang (-O0 with sanitizers).
#ifdef __SANITIZE_ADDRESS__
  constexpr bool sanitized = true;
#else
  constexpr bool sanitized = false;
#endif
  constexpr double        run_timeout_seconds = sanitized ? 200. : 20.;
  constexpr std::uint32_t default_seed        = 14; // fixed: the same mutants everywhere
  constexpr rlim_t        memory_limit        = rlim_t(4) << 30; // bytes per run


  struct Mutant
  {
    std::string       kind; // "<seed file> <mutation>"
    std::string       description;
    std::string       text;
    bool              is_mesh   = false;
    bool              timed_out = false; // the run: killed after the timeout,
    int               status    = 0;     // or its status from waitpid,
    Clock::time_point start;             // its start,
    double            seconds = 0.;      // its wall time,
    std::string       problem;           // and how it broke the contract ("" if not)
  };

  struct Plan
  {
    const char *name;
    Mutation    mutation;
    unsigned    n_prm;  // mutants of the parameter seed
    unsigned    n_mesh; // mutants of each mesh seed
  };

  // How many mutants of each kind; byte-level ones (no function) by mutate_bytes.
  const std::vector<Plan> plans = {{"flip", nullptr, 10, 6},
                                   {"delete", nullptr, 10, 6},
                                   {"insert-bytes", nullptr, 8, 5},
                                   {"insert-token", nullptr, 12, 5},
                                   {"repeat", nullptr, 6, 5},
                                   {"truncate", nullptr, 6, 6},
                                   {"splice", splice_lines, 8, 6},
                                   {"value", replace_value, 40, 0},
                                   {"drop-end", drop_end, 4, 0},
                                   {"repeat-subsection", repeat_subsection, 6, 0},
                                   {"include", add_include, 6, 0},
                                   {"token", replace_token, 0, 18},
                                   {"section", mutate_section, 0, 6},
                                   {"header", replace_header, 0, 6}};


  std::string
  read_file(const fs::path &path)
  {
    std::ifstream in(path, std::ios::binary);
    if (!in)
      throw std::runtime_error("cannot read " + path.string());
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  void
  write_file(const fs::path &path, const std::string &text)
  {
    std::ofstream(path, std::ios::binary) << text;
  }


  double
  seconds_since(const Clock::time_point start)
  {
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

  // Starts clothsim on mutant `index` (SCRATCH/mutant-N/mutant.prm, output SCRATCH/out-N,
  // stderr to SCRATCH/stderr-N.txt) in a process group of its own, so that a hang is
  // killed with all it started. No core dumps; 4 GB of address space at most (with
  // AddressSanitizer: 4 GB per allocation, above).
  pid_t
  start_run(const std::string &clothsim, const fs::path &scratch, const std::size_t index)
  {
    const std::string n   = std::to_string(index);
    const pid_t       pid = fork();
    if (pid != 0)
      return pid;
    setpgid(0, 0);
#ifdef __linux__
    prctl(PR_SET_PDEATHSIG, SIGKILL);
#endif
    const rlimit no_core{0, 0}, memory{memory_limit, memory_limit};
    setrlimit(RLIMIT_CORE, &no_core);
    if (sanitized)
      {
        const char       *given = std::getenv("ASAN_OPTIONS");
        const std::string options =
          std::string(given != nullptr ? given : "") +
          ":allocator_may_return_null=1:max_allocation_size_mb=" +
          std::to_string(memory_limit >> 20);
        setenv("ASAN_OPTIONS", options.c_str(), 1);
      }
    else
      setrlimit(RLIMIT_AS, &memory);
    // Open MPI's session directory per run: concurrent singletons sharing one race in
    // creating and removing it (MPI_Init then fails, which is not clothsim's doing).
    const std::string session = (scratch / ("mpi-" + n)).string();
    mkdir(session.c_str(), 0700);
    setenv("OMPI_MCA_orte_tmpdir_base", session.c_str(), 1);
    setenv("TMPDIR", session.c_str(), 1);
    const std::string errors = (scratch / ("stderr-" + n + ".txt")).string();
    const std::string out    = (scratch / ("out-" + n)).string();
    const int         null   = open("/dev/null", O_RDWR);
    const int error_file     = open(errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (null < 0 || error_file < 0 || chdir((scratch / ("mutant-" + n)).c_str()) != 0)
      _exit(127);
    dup2(null, 0);
    dup2(null, 1);
    dup2(error_file, 2);
    const char *argv[] = {
      clothsim.c_str(), "mutant.prm", "--output-dir", out.c_str(), nullptr};
    execv(clothsim.c_str(), const_cast<char *const *>(argv));
    const std::string message = "fuzz_inputs: cannot execute " + clothsim + "\n";
    (void)!write(2, message.data(), message.size());
    _exit(127);
  }

  // Runs all `mutants` (their files in place), at most `n_jobs` at a time.
  void
  run_all(const std::string   &clothsim,
          const fs::path      &scratch,
          std::vector<Mutant> &mutants,
          const unsigned       n_jobs)
  {
    std::map<pid_t, std::size_t> running; // process -> mutant
    for (std::size_t next = 0; next < mutants.size() || !running.empty();)
      {
        for (; next < mutants.size() && running.size() < n_jobs; ++next)
          {
            mutants[next].start = Clock::now();
            const pid_t pid     = start_run(clothsim, scratch, next);
            if (pid < 0)
              throw std::runtime_error("fork failed");
            running[pid] = next;
          }
        int         status = 0;
        const pid_t pid    = waitpid(-1, &status, WNOHANG);
        for (auto it = running.begin(); it != running.end();)
          {
            Mutant &mutant   = mutants[it->second];
            mutant.seconds   = seconds_since(mutant.start);
            mutant.timed_out = it->first != pid && mutant.seconds > run_timeout_seconds;
            if (mutant.timed_out)
              {
                kill(-it->first, SIGKILL);
                waitpid(it->first, &mutant.status, 0);
              }
            else if (it->first == pid)
              mutant.status = status;
            else
              {
                ++it;
                continue;
              }
            it = running.erase(it);
          }
        if (pid <= 0)
          std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
  }


  // What is wrong with a run, or "" if it kept the contract. `directory`: the mutant's,
  // which holds its input files only.
  std::string
  violation(const Mutant      &outcome,
            const std::string &errors,
            const fs::path    &directory,
            const fs::path    &out)
  {
    if (outcome.timed_out)
      return "no exit within " + std::to_string(int(run_timeout_seconds)) +
             " s (hang; killed)";
    if (WIFSIGNALED(outcome.status))
      return "killed by signal " + std::to_string(WTERMSIG(outcome.status)) + " (" +
             strsignal(WTERMSIG(outcome.status)) + ")";
    const int code = WEXITSTATUS(outcome.status);
    if (code != 0 && code != 1 && code != 2)
      return "exit code " + std::to_string(code);
    if (code != 1)
      return "";
    const std::string line = !errors.empty() && errors.back() == '\n'
                               ? errors.substr(0, errors.size() - 1)
                               : errors;
    if (line.compare(0, 17, "clothsim: error: ") != 0)
      return "exit code 1, but stderr does not start with 'clothsim: error: '";
    if (line.find('\n') != std::string::npos)
      return "exit code 1, but stderr has more than one line";
    if (fs::exists(fs::symlink_status(out)))
      return "exit code 1, but the output directory was created";
    for (const auto &entry : fs::directory_iterator(directory))
      if (std::set<std::string>{"mutant.prm", "mutant.msh", "mesh.msh"}.count(
            entry.path().filename().string()) == 0)
        return "exit code 1, but it wrote " + entry.path().string();
    return "";
  }

  // Mutants per kind and exit class, the slowest run, the wall time.
  void
  print_summary(const std::vector<Mutant> &mutants,
                const std::uint32_t        seed,
                const unsigned             n_jobs,
                const double               wall_seconds)
  {
    const std::vector<std::string> classes = {
      "0", "1", "2", "signal", "timeout", "other", "failed"};
    std::map<std::string, std::map<std::string, unsigned>> counts; // kind, class
    std::size_t                                            slowest = 0;
    for (std::size_t i = 0; i < mutants.size(); ++i)
      {
        const int         code       = WEXITSTATUS(mutants[i].status);
        const std::string exit_class = mutants[i].timed_out             ? "timeout"
                                       : WIFSIGNALED(mutants[i].status) ? "signal"
                                       : code <= 2 ? std::to_string(code)
                                                   : "other";
        for (const std::string &kind : {mutants[i].kind, std::string("total")})
          {
            ++counts[kind][exit_class];
            counts[kind]["failed"] += !mutants[i].problem.empty();
          }
        if (mutants[i].seconds > mutants[slowest].seconds)
          slowest = i;
      }
    std::cout << "\nfuzz_inputs: " << mutants.size() << " mutants (seed " << seed << "), "
              << n_jobs << " run(s) at a time; by exit code:\n"
              << std::left << std::setw(34) << "kind" << std::right;
    for (const std::string &c : classes)
      std::cout << std::setw(8) << c;
    std::cout << "\n";
    for (auto &[kind, row] : counts)
      {
        std::cout << std::left << std::setw(34) << kind << std::right;
        for (const std::string &c : classes)
          std::cout << std::setw(8) << row[c];
        std::cout << "\n";
      }
    std::cout << std::setprecision(3) << "slowest run: mutant " << slowest << " ["
              << mutants[slowest].kind << "] "
              << mutants[slowest].description.substr(0, 70) << ": "
              << mutants[slowest].seconds << " s\nwall time " << wall_seconds << " s; "
              << counts["total"]["failed"] << " mutant(s) broke the contract"
              << std::endl;
  }
} // namespace


int
main(int argc, char **argv)
{
  const auto               wall_start = Clock::now();
  std::vector<std::string> args(argv + 1, argv + argc);
  unsigned      n_jobs = std::min(2u, std::max(1u, std::thread::hardware_concurrency()));
  std::uint32_t seed   = default_seed;
  while (args.size() >= 2 && (args[0] == "--jobs" || args[0] == "--seed"))
    {
      (args[0] == "--jobs" ? n_jobs : seed) = std::stoul(args[1]);
      args.erase(args.begin(), args.begin() + 2);
    }
  if (args.size() < 4 || n_jobs == 0)
    {
      std::cerr
        << "usage: fuzz_inputs [--jobs N] [--seed S] CLOTHSIM SEED.prm SEED.msh... "
           "SCRATCH_DIR\n";
      return 2;
    }
  // MPI singleton start without a daemon, self transport only: 0.7 s a run, not 1.3 s.
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
  setenv("OMPI_MCA_btl", "self", 0);
  setenv("OMPI_MCA_pml", "ob1", 0);
  const std::string clothsim = fs::absolute(args[0]).string();
  const fs::path    scratch  = fs::absolute(args.back());
  if (access(clothsim.c_str(), X_OK) != 0)
    {
      std::cerr << "fuzz_inputs: " << clothsim << " is not executable\n";
      return 2;
    }

  // All mutants first (they do not depend on the runs), from one fixed random sequence.
  // Parameter mutants use the first mesh seed, mesh mutants the parameter seed.
  Context                  context{std::mt19937(seed), {}};
  std::vector<std::string> seed_names;
  for (std::size_t i = 1; i + 1 < args.size(); ++i)
    {
      seed_names.push_back(fs::path(args[i]).filename().string());
      context.seeds.push_back(read_file(args[i]));
    }
  const std::regex  mesh_entry("(set +Mesh file *=)[^\n]*");
  const std::string prm_base =
    std::regex_replace(context.seeds[0], mesh_entry, "$1 mesh.msh");
  const std::string mesh_prm =
    std::regex_replace(context.seeds[0], mesh_entry, "$1 mutant.msh");
  std::vector<Mutant> mutants;
  for (std::size_t s = 0; s < seed_names.size(); ++s)
    for (const Plan &plan : plans)
      for (unsigned n = (s == 0 ? plan.n_prm : plan.n_mesh); n > 0; --n)
        {
          Mutant mutant;
          mutant.kind             = seed_names[s] + " " + plan.name;
          mutant.is_mesh          = s > 0;
          const std::string &text = s == 0 ? prm_base : context.seeds[s];
          mutant.text             = plan.mutation
                                      ? plan.mutation(text, context, mutant.description)
                                      : mutate_bytes(plan.name, text, context, mutant.description);
          mutants.push_back(std::move(mutant));
        }

  // SCRATCH_DIR/mutant-N/: mutant.prm and mesh.msh, or the parameter seed and mutant.msh.
  fs::create_directories(scratch);
  for (const auto &entry : fs::directory_iterator(scratch))
    for (const std::string prefix : {"mutant-", "out-", "stderr-", "mpi-"})
      if (entry.path().filename().string().rfind(prefix, 0) == 0)
        fs::remove_all(entry.path());
  for (std::size_t i = 0; i < mutants.size(); ++i)
    {
      const fs::path directory = scratch / ("mutant-" + std::to_string(i));
      fs::create_directory(directory);
      const bool is_mesh = mutants[i].is_mesh;
      write_file(directory / "mutant.prm", is_mesh ? mesh_prm : mutants[i].text);
      write_file(directory / (is_mesh ? "mutant.msh" : "mesh.msh"),
                 is_mesh ? mutants[i].text : context.seeds[1]);
    }

  run_all(clothsim, scratch, mutants, n_jobs);

  std::size_t n_failed = 0;
  for (std::size_t i = 0; i < mutants.size(); ++i)
    {
      Mutant           &mutant      = mutants[i];
      const std::string n           = std::to_string(i);
      const fs::path    directory   = scratch / ("mutant-" + n);
      const fs::path    errors      = scratch / ("stderr-" + n + ".txt");
      const std::string stderr_text = read_file(errors);
      mutant.problem = violation(mutant, stderr_text, directory, scratch / ("out-" + n));
      if (mutant.problem.empty())
        {
          fs::remove_all(directory);
          fs::remove_all(scratch / ("out-" + n));
          fs::remove_all(scratch / ("mpi-" + n));
          fs::remove(errors);
          continue;
        }
      ++n_failed;
      std::cout << "FAILED mutant " << i << " [" << mutant.kind
                << "]: " << mutant.description << "\n  input:  "
                << (directory / (mutant.is_mesh ? "mutant.msh" : "mutant.prm")).string()
                << "\n  result: " << mutant.problem << " after " << std::setprecision(3)
                << mutant.seconds << " s\n  stderr: " << escaped(stderr_text, 600)
                << "\n";
    }
  print_summary(mutants, seed, n_jobs, seconds_since(wall_start));
  return n_failed == 0 ? 0 : 1;
}
