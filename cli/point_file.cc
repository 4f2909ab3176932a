#include "cli/point_file.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include <alignset/npy.h>

#include "client/whole_file.h"

namespace alignset::cli {
namespace {

std::string Shape(const std::vector<size_t>& dims) { return NpyShapeText(dims); }

// ------------------------------------------------------------------ write

void AppendPair(std::string* out, const Point2& p, const char* format) {
  char buf[64];
  const int len = std::snprintf(buf, sizeof(buf), format, p.x, p.y);
  out->append(buf, static_cast<size_t>(len));
}

StatusOr<std::string> Serialize(const std::string& path, const std::vector<PointSet>& sets,
                                bool several, const std::string& comment) {
  std::string out;
  switch (FileFormatOf(path)) {
    case FileFormat::kNpy: {
      const size_t n = sets.empty() ? 0 : sets[0].size();
      for (const PointSet& s : sets) {
        if (s.size() != n) {
          return Status::InvalidArgument(path + ": the sets have different sizes (" +
                                         std::to_string(n) + " and " + std::to_string(s.size()) +
                                         "), which an (m, N, 2) .npy array cannot hold");
        }
      }
      out = several ? NpyHeader({sets.size(), n, 2}) : NpyHeader({n, 2});
      for (const PointSet& s : sets) {
        out.append(reinterpret_cast<const char*>(s.data()), s.size() * sizeof(Point2));
      }
      return out;
    }
    case FileFormat::kCsv:
      // CSV has no comments: the metadata stays in text and .npy files' neighbours.
      out = several ? "set,x,y\n" : "x,y\n";
      for (size_t i = 0; i < sets.size(); ++i) {
        for (const Point2& p : sets[i]) {
          if (several) out += std::to_string(i) + ",";
          AppendPair(&out, p, "%.17g,%.17g\n");
        }
      }
      return out;
    case FileFormat::kText: {
      std::istringstream lines(comment);
      for (std::string line; std::getline(lines, line);) out += "# " + line + "\n";
      for (size_t i = 0; i < sets.size(); ++i) {
        // UTK's separator: a '#' line between sets.
        if (i > 0) out += "#\n";
        for (const Point2& p : sets[i]) AppendPair(&out, p, "%.17g %.17g\n");
      }
      return out;
    }
  }
  return out;
}

Status WriteAll(const std::string& path, const std::string& data) {
  if (IsStdStream(path)) {
    if (std::fwrite(data.data(), 1, data.size(), stdout) != data.size() || std::fflush(stdout) != 0) {
      return Status::InvalidArgument(std::string("cannot write to standard output: ") +
                                     std::strerror(errno));
    }
    return Status::Ok();
  }
  return WriteWholeFile(path, data);
}

// ------------------------------------------------------------------- read

Status CheckInside(const std::string& path, const std::vector<PointSet>& sets) {
  for (size_t s = 0; s < sets.size(); ++s) {
    for (size_t i = 0; i < sets[s].size(); ++i) {
      const Point2& p = sets[s][i];
      if (!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0)) {
        char where[160];
        std::snprintf(where, sizeof(where), ": point %zu%s (%.17g, %.17g) lies outside [0, 1)^2", i,
                      sets.size() > 1 ? (" of set " + std::to_string(s)).c_str() : "", p.x, p.y);
        return Status::InvalidArgument(path + where);
      }
    }
  }
  return Status::Ok();
}

StatusOr<std::vector<PointSet>> ParseNpy(const std::string& data, const std::string& path) {
  auto array = ParseNpyArray(data, path);
  if (!array.ok()) return array.status();
  const std::vector<size_t>& dims = array->shape;
  // Element at a multi-index (the values are in C order).
  auto at = [&](std::initializer_list<size_t> idx) {
    size_t flat = 0, k = 0;
    for (size_t i : idx) flat = flat * dims[k++] + i;
    return array->values[flat];
  };
  // A shape with no points holds no values, so the body's length does not
  // bound its other dimensions: (10^10, 0, 2) would allocate 10^10 empty sets.
  for (size_t d : dims) {
    if (d == 0) return Status::InvalidArgument(path + ": shape " + Shape(dims) + " holds no points");
  }
  std::vector<PointSet> sets;
  if (dims.size() == 2 && dims[1] == 2) {  // (N, 2): the documented layout
    PointSet s(dims[0]);
    for (size_t i = 0; i < dims[0]; ++i) s[i] = {at({i, 0}), at({i, 1})};
    sets.push_back(std::move(s));
  } else if (dims.size() == 2 && dims[0] == 2) {  // (2, N), N != 2: x row, y row
    PointSet s(dims[1]);
    for (size_t i = 0; i < dims[1]; ++i) s[i] = {at({0, i}), at({1, i})};
    sets.push_back(std::move(s));
  } else if (dims.size() == 3 && dims[2] == 2) {  // (m, N, 2)
    for (size_t m = 0; m < dims[0]; ++m) {
      PointSet s(dims[1]);
      for (size_t i = 0; i < dims[1]; ++i) s[i] = {at({m, i, 0}), at({m, i, 1})};
      sets.push_back(std::move(s));
    }
  } else if (dims.size() == 1) {
    return Status::InvalidArgument(path + ": a flat array of " + std::to_string(dims[0]) +
                                   " values; points need shape (N, 2) (numpy: a.reshape(-1, 2))");
  } else {
    return Status::InvalidArgument(path + ": shape " + Shape(dims) +
                                   " is not (N, 2), (2, N) or (m, N, 2)");
  }
  return sets;
}

// A finite number filling the whole field.
bool ParseNumber(const std::string& text, double* v) {
  const char* begin = text.c_str();
  while (*begin == ' ' || *begin == '\t') ++begin;
  char* end = nullptr;
  errno = 0;
  *v = std::strtod(begin, &end);
  if (end == begin || errno == ERANGE || !std::isfinite(*v)) return false;
  while (*end == ' ' || *end == '\t' || *end == '\r') ++end;
  return *end == '\0';
}

StatusOr<std::vector<PointSet>> ParseCsv(const std::string& data, const std::string& path) {
  std::vector<PointSet> sets;
  std::istringstream lines(data);
  int line_no = 0;
  int columns = 0;  // 2: x,y; 3: set,x,y
  for (std::string line; std::getline(lines, line);) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
    const std::string where = path + ":" + std::to_string(line_no) + ": ";
    if (columns == 0 && sets.empty()) {
      std::string header;
      for (char c : line) {
        if (c != ' ' && c != '\r') header += c;
      }
      if (header == "x,y" || header == "set,x,y") {
        columns = header == "x,y" ? 2 : 3;
        continue;
      }
    }
    if (columns == 0) columns = static_cast<int>(fields.size());
    if (static_cast<int>(fields.size()) != columns || (columns != 2 && columns != 3)) {
      return Status::InvalidArgument(where + (columns == 3 ? "expected \"set,x,y\"" : "expected \"x,y\""));
    }
    size_t set = 0;
    if (columns == 3) {
      double s = 0;
      if (!ParseNumber(fields[0], &s) || s < 0 || s != std::floor(s) || s > sets.size()) {
        return Status::InvalidArgument(where + "the set column must count 0, 1, ... in order");
      }
      set = static_cast<size_t>(s);
    }
    Point2 p;
    if (!ParseNumber(fields[columns - 2], &p.x) || !ParseNumber(fields[columns - 1], &p.y)) {
      return Status::InvalidArgument(where + "expected two finite numbers x,y");
    }
    if (set == sets.size()) sets.emplace_back();
    if (set + 1 != sets.size()) {
      return Status::InvalidArgument(where + "the rows of each set must be together, sets in order");
    }
    sets.back().push_back(p);
  }
  return sets;
}

StatusOr<std::vector<PointSet>> ParseText(const std::string& data, const std::string& path) {
  std::vector<PointSet> sets(1);
  std::istringstream lines(data);
  int line_no = 0;
  for (std::string line; std::getline(lines, line);) {
    ++line_no;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    if (line[first] == '#') {
      // UTK: a '#' line closes the set before it (if it has points).
      if (!sets.back().empty()) sets.emplace_back();
      continue;
    }
    std::istringstream fields(line);
    Point2 p;
    std::string extra;
    if (!(fields >> p.x >> p.y) || (fields >> extra) || !std::isfinite(p.x) || !std::isfinite(p.y)) {
      return Status::InvalidArgument(path + ":" + std::to_string(line_no) +
                                     ": expected two finite numbers \"x y\"");
    }
    sets.back().push_back(p);
  }
  if (sets.back().empty()) sets.pop_back();
  return sets;
}

}  // namespace

bool IsStdStream(const std::string& path) { return path == "-"; }

FileFormat FileFormatOf(const std::string& path) {
  auto ends_with = [&path](const char* suffix) {
    const size_t n = std::strlen(suffix);
    return path.size() >= n && path.compare(path.size() - n, n, suffix) == 0;
  };
  if (IsStdStream(path)) return FileFormat::kText;
  if (ends_with(".npy")) return FileFormat::kNpy;
  if (ends_with(".csv")) return FileFormat::kCsv;
  return FileFormat::kText;
}

FILE* ReportStreamFor(const std::string& out_path) { return IsStdStream(out_path) ? stderr : stdout; }

Status WritePointSets(const std::string& path, const std::vector<PointSet>& sets,
                      const std::string& comment) {
  if (path.empty()) return Status::InvalidArgument("output path is empty");
  auto data = Serialize(path, sets, true, comment);
  if (!data.ok()) return data.status();
  return WriteAll(path, *data);
}

Status WritePointFile(const std::string& path, const PointSet& points, const std::string& comment) {
  if (path.empty()) return Status::InvalidArgument("output path is empty");
  auto data = Serialize(path, {points}, false, comment);
  if (!data.ok()) return data.status();
  return WriteAll(path, *data);
}

StatusOr<std::vector<PointSet>> ReadPointSets(const std::string& path) {
  std::string data;
  if (IsStdStream(path)) {
    data.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
  } else {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Status::InvalidArgument("cannot read " + path + ": " + std::strerror(errno));
    data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return ParsePointSets(data, path);
}

StatusOr<std::vector<PointSet>> ParsePointSets(const std::string& data, const std::string& path) {
  const FileFormat format = FileFormatOf(path);
  auto sets = format == FileFormat::kNpy   ? ParseNpy(data, path)
              : format == FileFormat::kCsv ? ParseCsv(data, path)
                                       : ParseText(data, path);
  if (!sets.ok()) return sets.status();
  if (sets->empty()) return Status::InvalidArgument(path + ": no points");
  for (const PointSet& s : *sets) {
    if (s.empty()) return Status::InvalidArgument(path + ": a set without points");
  }
  if (Status s = CheckInside(path, *sets); !s.ok()) return s;
  return sets;
}

StatusOr<PointSet> ReadPointFile(const std::string& path) {
  auto sets = ReadPointSets(path);
  if (!sets.ok()) return sets.status();
  if (sets->size() > 1) {
    return Status::InvalidArgument(path + " holds " + std::to_string(sets->size()) +
                                   " point sets ('#'-separated or (m, N, 2)); this command reads "
                                   "one: split the file, or use a command that reads several");
  }
  return std::move(sets->front());
}

}  // namespace alignset::cli
