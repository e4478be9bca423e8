// InputReplay: a LAMMPS input replayed on top of a restart (see the header).
#include "input_replay.h"

#include "lammps_coupling_host.h"

#include "input.h"
#include "lammps.h"
#include "memory.h"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

using namespace LAMMPS_NS;

namespace meltdem {

namespace {

bool one_of(const std::string &w, std::initializer_list<const char *> names)
{
  for (const char *n : names)
    if (w == n) return true;
  return false;
}

// fix styles that write a file named after their 'file' keyword and cannot append
bool averaging_fix(const std::string &style)
{
  return style.rfind("ave/", 0) == 0;
}

// LAMMPS's word splitting: white space separates, "..." '...' """...""" keep a word
std::vector<std::string> split_words(const std::string &text)
{
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    if (i >= text.size()) break;
    std::string w;
    if (text.compare(i, 3, "\"\"\"") == 0) {
      const std::size_t end = text.find("\"\"\"", i + 3);
      const std::size_t stop = end == std::string::npos ? text.size() : end + 3;
      w = text.substr(i, stop - i);
      i = stop;
    } else {
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) {
        if (text[i] == '"' || text[i] == '\'') {
          const char q = text[i];
          const std::size_t end = text.find(q, i + 1);
          const std::size_t stop = end == std::string::npos ? text.size() : end + 1;
          w += text.substr(i, stop - i);
          i = stop;
        } else {
          w += text[i++];
        }
      }
    }
    words.push_back(w);
  }
  return words;
}

// the text before a '#' that is outside quotes
std::string without_comment(const std::string &line)
{
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#') {
      return line.substr(0, i);
    }
  }
  return line;
}

void read_into(const std::string &file, std::vector<InputCommand> &out, int depth)
{
  if (depth > 16) throw LammpsSetupError("LAMMPS input " + file + ": include nested more than 16 deep");
  std::ifstream in(file);
  if (!in) throw LammpsSetupError("cannot open the LAMMPS input file " + file);
  std::string line, command;
  int n = 0, first = 0;
  while (std::getline(in, line)) {
    ++n;
    if (command.empty()) first = n;
    const auto last = line.find_last_not_of(" \t\r");
    if (last != std::string::npos && line[last] == '&') {
      command += line.substr(0, last) + ' ';
      continue;
    }
    command += line;
    const std::string text = without_comment(command);
    command.clear();
    std::vector<std::string> words = split_words(text);
    if (words.empty()) continue;
    const std::string where = file + ":" + std::to_string(first);
    const std::string &w = words.front();
    if (one_of(w, {"jump", "label", "next", "clear"}))
      throw LammpsSetupError("cannot replay the LAMMPS input " + where + ": its '" + w +
                             "' command cannot be replayed command by command on a restart (write the input without "
                             "loops, jumps and clear)");
    if (w == "include") {
      if (words.size() < 2 || words[1].find('$') != std::string::npos)
        throw LammpsSetupError("cannot replay the LAMMPS input " + where +
                               ": an include without a plain file name (variables are known only while it runs)");
      read_into(words[1], out, depth + 1);
      continue;
    }
    out.push_back({text, std::move(words), where});
  }
}

bool file_size(const std::string &path, long long &size)
{
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return false;
  size = (long long)st.st_size;
  return true;
}

}  // namespace

std::vector<InputCommand> read_input_commands(const std::string &file)
{
  std::vector<InputCommand> out;
  read_into(file, out, 0);
  return out;
}

std::string substituted(LAMMPS *lmp, const std::string &text)
{
  if (text.find('$') == std::string::npos) return text;
  int max = int(text.size()) + 1, max2 = max;
  char *str = static_cast<char *>(lmp->memory->smalloc(max, "meltdem:substitute"));
  char *work = static_cast<char *>(lmp->memory->smalloc(max2, "meltdem:substitute"));
  std::strcpy(str, text.c_str());
  lmp->input->substitute(str, work, max, max2, 0);
  std::string out(str);
  lmp->memory->sfree(str);
  lmp->memory->sfree(work);
  return out;
}

void write_executed_commands(const std::string &file, const std::vector<InputCommand> &commands,
                             const std::vector<std::string> &executed)
{
  std::ofstream os(file, std::ios::trunc);
  for (std::size_t i = 0; i < executed.size() && i < commands.size(); ++i)
    if (!executed[i].empty()) os << i << '\n' << commands[i].text << '\n' << executed[i] << '\n';
  os.close();
  if (!os) throw LammpsSetupError("cannot write " + file + ": " + std::strerror(errno));
}

std::vector<std::string> read_executed_commands(const std::string &file, const std::vector<InputCommand> &commands)
{
  std::vector<std::string> executed(commands.size());
  std::ifstream in(file);
  std::string index, original, text;
  while (std::getline(in, index) && std::getline(in, original) && std::getline(in, text)) {
    const std::size_t i = std::strtoull(index.c_str(), nullptr, 10);
    if (i < commands.size() && commands[i].text == original) executed[i] = text;
  }
  return executed;
}

std::vector<std::string> output_files(LAMMPS *lmp, const std::vector<InputCommand> &commands)
{
  std::vector<std::string> files;
  auto add = [&](const std::string &f) {
    if (std::find(files.begin(), files.end(), f) == files.end()) files.push_back(f);
  };
  for (const InputCommand &c : commands) {
    const std::string &w = c.name();
    if (w != "dump" && w != "fix") continue;
    const std::vector<std::string> words = split_words(substituted(lmp, c.text));
    if (w == "dump" && words.size() > 5) {
      const std::string &f = words[5];
      // one file per step or per processor: each frame is its own file, nothing to continue
      if (f.find('*') == std::string::npos && f.find('%') == std::string::npos) add(f);
    } else if (w == "fix" && words.size() > 3 && (averaging_fix(words[3]) || words[3] == "print")) {
      for (std::size_t k = 4; k + 1 < words.size(); ++k)
        if (words[k] == "file" || (words[3] == "print" && words[k] == "append")) add(words[k + 1]);
    }
  }
  return files;
}

OutputSizes output_sizes(const std::vector<std::string> &files)
{
  OutputSizes sizes;
  for (const std::string &f : files) {
    long long s = -1;
    if (!file_size(f, s)) s = -1;
    sizes.emplace_back(f, s);
  }
  return sizes;
}

void write_output_sizes(const std::string &file, const OutputSizes &sizes)
{
  std::ofstream os(file, std::ios::trunc);
  for (const auto &s : sizes) os << s.second << ' ' << s.first << '\n';
  os.close();
  if (!os) throw LammpsSetupError("cannot write " + file + ": " + std::strerror(errno));
}

OutputSizes read_output_sizes(const std::string &file)
{
  OutputSizes sizes;
  std::ifstream in(file);
  long long s;
  std::string name;
  while (in >> s && std::getline(in >> std::ws, name)) sizes.emplace_back(name, s);
  return sizes;
}

InputReplay::InputReplay(std::string restart_file, OutputSizes outputs) :
    restart_file_(std::move(restart_file)), outputs_(std::move(outputs))
{
}

void InputReplay::remove_scratch() const
{
  for (const Redirect &r : redirects_) std::remove(r.scratch.c_str());
}

void InputReplay::rewind_outputs() const
{
  for (const auto &o : outputs_) {
    long long now = 0;
    if (!file_size(o.first, now)) continue;
    if (o.second < 0) {
      std::remove(o.first.c_str());
    } else if (now > o.second && ::truncate(o.first.c_str(), (off_t)o.second) != 0) {
      throw LammpsSetupError("cannot cut the output file " + o.first +
                             " back to its checkpoint: " + std::strerror(errno));
    }
  }
}

std::vector<std::string> InputReplay::before_checkpoint(LAMMPS *lmp, const InputCommand &command)
{
  const std::string &w = command.name();
  if (w == "read_restart" || w == "create_box" ||
      (w == "read_data" && std::find(command.words.begin(), command.words.end(), "add") == command.words.end())) {
    if (box_done_) return {};
    box_done_ = true;
    return {"read_restart " + restart_file_};
  }
  // what made or changed the state (the restart holds it), and what would write files
  if (one_of(w, {"create_atoms",  "read_data",      "velocity",      "set",          "displace_atoms", "delete_atoms",
                 "run",           "minimize",       "write_restart", "write_data",   "write_dump",     "write_coeff",
                 "change_box",    "reset_timestep", "create_bonds",  "delete_bonds", "rerun",          "read_dump",
                 "group",         "timestep",       "replicate",     "balance",      "print",          "shell",
                 "reset_atom_ids"}))
    return {};
  std::vector<std::string> words = split_words(substituted(lmp, command.text));
  if (w == "dump" && words.size() > 1) return {command.text, "dump_modify " + words[1] + " append yes"};
  if (w == "log" && words.size() > 1) return {"log " + words[1] + " append"};
  if (w == "fix" && words.size() > 3 && (words[3] == "print" || averaging_fix(words[3]))) {
    for (std::size_t k = 4; k + 1 < words.size(); ++k) {
      if (words[k] != "file") continue;
      if (words[3] == "print") {
        words[k] = "append";
      } else {
        const auto at = std::find_if(outputs_.begin(), outputs_.end(), [&](const std::pair<std::string, long long> &o) {
          return o.first == words[k + 1];
        });
        if (at == outputs_.end() || at->second < 0) continue;  // not written before the checkpoint: starts anew
        Redirect r;
        r.target = words[k + 1];
        r.scratch = r.target + ".resumed";
        words[k + 1] = r.scratch;
        redirects_.push_back(r);
      }
    }
    std::string text;
    for (const std::string &x : words) text += (text.empty() ? "" : " ") + x;
    return {text};
  }
  return {command.text};
}

std::vector<std::string> InputReplay::before_checkpoint(LAMMPS *lmp, const InputCommand &command, std::string &executed)
{
  if (executed.empty()) {
    executed = substituted(lmp, command.text);
    return before_checkpoint(lmp, command);
  }
  InputCommand as_run = command;
  as_run.text = executed;
  return before_checkpoint(lmp, as_run);
}

void InputReplay::merge_outputs()
{
  for (Redirect &r : redirects_) {
    std::ifstream in(r.scratch, std::ios::binary);
    if (!in) continue;
    in.seekg(r.merged);
    std::string fresh((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // whole lines only: the fix flushes each output, a partial line is still being written
    const std::size_t end = fresh.rfind('\n');
    if (end == std::string::npos) continue;
    fresh.resize(end + 1);
    r.merged += (long long)fresh.size();
    std::size_t from = 0;
    if (!r.header_done) {
      // the header the fix writes when created is already in the file
      while (from < fresh.size() && fresh[from] == '#') from = fresh.find('\n', from) + 1;
      r.header_done = true;
    }
    std::ofstream out(r.target, std::ios::app | std::ios::binary);
    out.write(fresh.data() + from, std::streamsize(fresh.size() - from));
    out.close();
    if (!out) throw LammpsSetupError("cannot append to the output file " + r.target + ": " + std::strerror(errno));
  }
}

}  // namespace meltdem
