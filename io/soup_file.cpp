#include "io/soup_file.h"

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <CGAL/IO/read_ply_points.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <limits>
#include <locale>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "io/detail/soup_file_binary_check.h"
#include "io/detail/soup_file_lines.h"
#include "io/detail/soup_file_ply_header.h"
#include "io/detail/soup_file_text_check.h"

namespace shadowcert {

namespace {

namespace fs = std::filesystem;
namespace detail = soup_file_detail;

// Simple_cartesian<double> points hold the file's doubles unchanged, and every CGAL reader
// accepts them (the OFF and PLY readers need a kernel point; std::array is not one).
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Polygon = std::vector<std::size_t>;

// What a CGAL reader produced, plus where its records sit in a text file.
struct PolygonSoup {
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  std::vector<Normal> normals;
  detail::RecordLines lines;  // empty for binary files: messages name elements instead
};

enum class Format { obj, off, ply, stl };

constexpr const char* kReadable = "read_soup reads .obj, .off, .ply and .stl";

std::string lowercase_extension(const fs::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

std::optional<Format> format_named(const std::string& extension) {
  if (extension == ".obj") return Format::obj;
  if (extension == ".off") return Format::off;
  if (extension == ".ply") return Format::ply;
  if (extension == ".stl") return Format::stl;
  return std::nullopt;
}

Format readable_format(const fs::path& file, const std::string& name) {
  const std::string extension = lowercase_extension(file);
  if (const auto format = format_named(extension)) return *format;
  if (extension.empty()) detail::fail(name, 0, std::string("no file extension (") + kReadable + ")");
  detail::fail(name, 0, "unknown extension " + detail::quoted(extension) + " (" + kReadable + ")");
}

void check_is_file(const fs::path& file, const std::string& name) {
  std::error_code error;
  const fs::file_status status = fs::status(file, error);
  if (!fs::exists(status)) detail::fail(name, 0, "no such file");
  if (fs::is_directory(status)) detail::fail(name, 0, "is a directory, not a mesh file");
}

std::string load(const fs::path& file, const std::string& name) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) detail::fail(name, 0, "cannot open the file for reading");
  const std::streamoff size = in.tellg();
  std::string data(size > 0 ? static_cast<std::size_t>(size) : 0, '\0');
  in.seekg(0);
  if (size < 0 || !in.read(data.data(), size)) detail::fail(name, 0, "cannot read the file");
  return data;
}

void check_not_blank(std::string_view data, const std::string& name) {
  if (data.empty()) detail::fail(name, 0, "empty file");
  if (data.find_first_not_of(" \t\r\n\v\f") == std::string_view::npos)
    detail::fail(name, 0, "empty file (only whitespace)");
}

// A stream over the file's bytes in the classic locale, whatever the global one is.
std::istringstream stream_of(std::string_view data) {
  std::istringstream in(std::string(data), std::ios::in | std::ios::binary);
  in.imbue(std::locale::classic());
  return in;
}

[[noreturn]] void fail_cgal(const std::string& name, const char* format) {
  detail::fail(name, 0,
               std::string("CGAL's ") + format + " reader rejected the file, though it passed the checks that "
                                                 "run before it");
}

// ------------------------------------------------------------------------- per format

PolygonSoup read_obj(std::string_view data, const std::string& name) {
  PolygonSoup soup;
  soup.lines = detail::check_obj_text(data, name);
  std::istringstream in = stream_of(data);
  if (!CGAL::IO::read_OBJ(in, soup.points, soup.polygons, CGAL::parameters::verbose(false)))
    fail_cgal(name, "OBJ");
  return soup;
}

PolygonSoup read_off(std::string_view data, const std::string& name) {
  PolygonSoup soup;
  soup.lines = detail::check_off_text(data, name);
  std::istringstream in = stream_of(data);
  // verbose defaults to true in CGAL's OFF reader.
  if (!CGAL::IO::read_OFF(in, soup.points, soup.polygons, CGAL::parameters::verbose(false)))
    fail_cgal(name, "OFF");
  return soup;
}

// A double normal component as a float; out-of-range values saturate to infinity
// (a plain cast would be undefined behaviour).
float to_float(double value) {
  if (std::fabs(value) > FLT_MAX) return value > 0 ? std::numeric_limits<float>::infinity()
                                                   : -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

// CGAL's polygon-soup PLY reader drops vertex normals; its point-set reader reads them
// (a second pass, only for files that have normals).
std::vector<Normal> read_ply_normals(std::string_view data, const std::string& name) {
  using Vector = Kernel::Vector_3;
  std::vector<Vector> vectors;
  std::istringstream in = stream_of(data);
  if (!CGAL::IO::read_PLY_with_properties(in, std::back_inserter(vectors),
                                          CGAL::IO::make_ply_normal_reader(CGAL::Identity_property_map<Vector>())))
    fail_cgal(name, "PLY normal");
  std::vector<Normal> normals;
  normals.reserve(vectors.size());
  for (const Vector& v : vectors) normals.push_back({to_float(v.x()), to_float(v.y()), to_float(v.z())});
  return normals;
}

PolygonSoup read_ply(std::string_view data, const std::string& name) {
  PolygonSoup soup;
  const detail::PlyHeader header = detail::read_ply_header(data, name);
  if (header.format == detail::PlyFormat::ascii)
    soup.lines = detail::check_ply_ascii_body(data, header, name);
  else
    detail::check_binary_ply_layout(data, header, name);
  std::istringstream in = stream_of(data);
  // verbose defaults to true in CGAL's PLY reader.
  if (!CGAL::IO::read_PLY(in, soup.points, soup.polygons, CGAL::parameters::verbose(false)))
    fail_cgal(name, "PLY");
  if (detail::has_ply_vertex_normals(header)) soup.normals = read_ply_normals(data, name);
  return soup;
}

PolygonSoup read_stl(std::string_view data, const std::string& name) {
  PolygonSoup soup;
  std::istringstream in = stream_of(data);
  bool read = false;
  // CGAL's public read_STL sniffs the encoding from the first word (see classify_stl), so
  // the encoding decided here goes straight to its two parsers.
  if (detail::classify_stl(data, name) == detail::StlEncoding::binary) {
    detail::check_binary_stl_coordinates(data, name);
    read = CGAL::IO::internal::parse_binary_STL(in, soup.points, soup.polygons, false);
  } else {
    // CGAL welds STL vertices, so only faces map to lines.
    soup.lines.face = detail::check_stl_ascii_text(data, name).face;
    read = CGAL::IO::internal::parse_ASCII_STL(in, soup.points, soup.polygons, false);
  }
  if (!read) fail_cgal(name, "STL");
  return soup;
}

PolygonSoup read_polygons(Format format, std::string_view data, const std::string& name) {
  switch (format) {
    case Format::obj: return read_obj(data, name);
    case Format::off: return read_off(data, name);
    case Format::ply: return read_ply(data, name);
    case Format::stl: return read_stl(data, name);
  }
  throw std::logic_error("read_soup: unhandled format");
}

// ------------------------------------------------------------- validation of CGAL's output

// The line check and CGAL must agree on how many records the file holds; if they ever do
// not, the file lies in a blind spot of the check, and refusing it beats guessing.
void check_agreement(const PolygonSoup& soup, const std::string& name) {
  const auto disagree = [&](const char* what, std::size_t cgal, std::size_t lines) {
    detail::fail(name, 0,
                 "CGAL's reader found " + std::to_string(cgal) + " " + what + " where the line check found " +
                     std::to_string(lines));
  };
  if (!soup.lines.vertex.empty() && soup.lines.vertex.size() != soup.points.size())
    disagree("vertices", soup.points.size(), soup.lines.vertex.size());
  if (!soup.lines.face.empty() && soup.lines.face.size() != soup.polygons.size())
    disagree("faces", soup.polygons.size(), soup.lines.face.size());
}

const char* axis_name(std::size_t axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

void check_points(const PolygonSoup& soup, const std::string& name) {
  if (soup.points.size() > std::numeric_limits<std::uint32_t>::max())
    detail::fail(name, 0,
                 std::to_string(soup.points.size()) + " vertices: more than the 4294967295 a soup can index");
  for (std::size_t k = 0; k < soup.points.size(); ++k)
    for (std::size_t axis = 0; axis < 3; ++axis)
      if (!std::isfinite(soup.points[k][static_cast<int>(axis)]))
        detail::fail(name, detail::line_of(soup.lines.vertex, k),
                     "vertex " + std::to_string(k) + ": coordinate " + axis_name(axis) + " is not finite (" +
                         std::to_string(soup.points[k][static_cast<int>(axis)]) + ")");
}

// CGAL stores a negative index (PLY int, OBJ relative) as its two's complement.
std::string index_text(std::size_t index) {
  if (index > static_cast<std::size_t>(std::numeric_limits<long long>::max()))
    return std::to_string(static_cast<long long>(index));
  return std::to_string(index);
}

void check_polygons(const PolygonSoup& soup, const std::string& name) {
  if (soup.polygons.empty()) detail::fail(name, 0, "the file has no face");
  const std::size_t vertex_count = soup.points.size();
  for (std::size_t j = 0; j < soup.polygons.size(); ++j) {
    const Polygon& polygon = soup.polygons[j];
    const std::size_t line = detail::line_of(soup.lines.face, j);
    if (polygon.size() < 3)
      detail::fail(name, line,
                   "face " + std::to_string(j) + " has " + std::to_string(polygon.size()) +
                       " vertices (a face needs at least 3)");
    for (const std::size_t index : polygon)
      if (index >= vertex_count)
        detail::fail(name, line,
                     "face " + std::to_string(j) + ": vertex index " + index_text(index) +
                         " is out of range (the file has " + std::to_string(vertex_count) + " vertices)");
  }
}

// Fan from the first corner: (v0, v1, v2), (v0, v2, v3), ... keeps the polygon's orientation.
Soup triangulate(const PolygonSoup& polygons) {
  Soup soup;
  soup.vertices.reserve(polygons.points.size());
  for (const Point& p : polygons.points) soup.vertices.push_back({p.x(), p.y(), p.z()});
  std::size_t triangle_count = 0;
  for (const Polygon& polygon : polygons.polygons) triangle_count += polygon.size() - 2;
  soup.triangles.reserve(triangle_count);
  for (const Polygon& polygon : polygons.polygons)
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
      soup.triangles.push_back({static_cast<std::uint32_t>(polygon[0]), static_cast<std::uint32_t>(polygon[i]),
                                static_cast<std::uint32_t>(polygon[i + 1])});
  if (polygons.normals.size() == polygons.points.size()) soup.normals = polygons.normals;
  return soup;
}

// The bytes of a file of a known format, checked and read, as read_soup returns them.
Soup soup_of(Format format, std::string_view data, const std::string& name) {
  check_not_blank(data, name);
  const PolygonSoup polygons = read_polygons(format, data, name);
  check_agreement(polygons, name);
  check_points(polygons, name);
  check_polygons(polygons, name);
  return triangulate(polygons);
}

// ---------------------------------------------------------------------------- writing

void check_writable(const Soup& soup) {
  for (std::size_t k = 0; k < soup.vertices.size(); ++k)
    for (const double c : soup.vertices[k])
      if (!std::isfinite(c))
        throw std::invalid_argument("write_soup: vertex " + std::to_string(k) + " has a non-finite coordinate");
  for (std::size_t j = 0; j < soup.triangles.size(); ++j)
    for (const std::uint32_t index : soup.triangles[j])
      if (index >= soup.vertices.size())
        throw std::invalid_argument("write_soup: triangle " + std::to_string(j) + " has index " +
                                    std::to_string(index) + " out of range");
  if (!soup.normals.empty() && soup.normals.size() != soup.vertices.size())
    throw std::invalid_argument("write_soup: normals must be empty or one per vertex");
}

void write_point(std::ostream& out, const char* prefix, const Vec3& v) {
  out << prefix << v[0] << ' ' << v[1] << ' ' << v[2];
}

void write_off(std::ostream& out, const Soup& soup) {
  out << "OFF\n" << soup.vertices.size() << ' ' << soup.triangles.size() << " 0\n";
  for (const Vec3& v : soup.vertices) {
    write_point(out, "", v);
    out << '\n';
  }
  for (const Triangle& t : soup.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

// OBJ counts from 1; widen first so that index 4294967295 does not wrap.
void write_obj(std::ostream& out, const Soup& soup) {
  out << "# shadowcert soup: " << soup.vertices.size() << " vertices, " << soup.triangles.size()
      << " triangles\n";
  for (const Vec3& v : soup.vertices) {
    write_point(out, "v ", v);
    out << '\n';
  }
  for (const Triangle& t : soup.triangles)
    out << "f " << std::uint64_t{t[0]} + 1 << ' ' << std::uint64_t{t[1]} + 1 << ' ' << std::uint64_t{t[2]} + 1
        << '\n';
}

void write_ply_header(std::ostream& out, const Soup& soup) {
  out << "ply\nformat ascii 1.0\ncomment shadowcert soup\n"
      << "element vertex " << soup.vertices.size() << "\n"
      << "property double x\nproperty double y\nproperty double z\n";
  if (!soup.normals.empty()) out << "property float nx\nproperty float ny\nproperty float nz\n";
  out << "element face " << soup.triangles.size() << "\n"
      << "property list uchar uint vertex_indices\nend_header\n";
}

void write_ply(std::ostream& out, const Soup& soup) {
  write_ply_header(out, soup);
  for (std::size_t k = 0; k < soup.vertices.size(); ++k) {
    write_point(out, "", soup.vertices[k]);
    if (!soup.normals.empty()) {
      // max_digits10 of float, so that normals round-trip too
      out << std::setprecision(std::numeric_limits<float>::max_digits10);
      for (const float c : soup.normals[k]) out << ' ' << c;
      out << std::setprecision(std::numeric_limits<double>::max_digits10);
    }
    out << '\n';
  }
  for (const Triangle& t : soup.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

}  // namespace

Soup read_soup(const fs::path& file) {
  if (file.empty()) throw std::invalid_argument("read_soup: empty path");
  const std::string name = file.string();
  check_is_file(file, name);
  const Format format = readable_format(file, name);
  return soup_of(format, load(file, name), name);
}

Soup parse_soup(std::string_view data, const std::string& file_name) {
  return soup_of(readable_format(fs::path(file_name), file_name), data, file_name);
}

void write_soup(const fs::path& file, const Soup& soup) {
  const std::string extension = lowercase_extension(file);
  if (extension != ".off" && extension != ".obj" && extension != ".ply")
    throw std::invalid_argument("write_soup: cannot write " + detail::quoted(file.string()) +
                                ": write_soup writes .off, .obj and .ply");
  check_writable(soup);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error("write_soup: cannot open '" + file.string() + "' for writing");
  out.imbue(std::locale::classic());
  // max_digits10: every double prints with enough digits to read back bitwise-equal.
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  if (extension == ".off") write_off(out, soup);
  else if (extension == ".obj") write_obj(out, soup);
  else write_ply(out, soup);
  out.close();
  if (!out) throw std::runtime_error("write_soup: writing '" + file.string() + "' failed");
}

}  // namespace shadowcert
