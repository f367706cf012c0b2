// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "vtu.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/error.hpp"
#include "output_file.hpp"

namespace dda::script {

namespace {

// ---- VTK XML binary arrays: base64 of a UInt64 byte count and the data ----------

void base64(const std::uint8_t* data, std::size_t n, std::string& out) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::size_t i = 0;
  for (; i + 2 < n; i += 3) {
    const std::uint32_t v = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
    out += k[v >> 18], out += k[(v >> 12) & 63], out += k[(v >> 6) & 63], out += k[v & 63];
  }
  if (i + 1 == n) {
    const std::uint32_t v = data[i] << 16;
    out += k[v >> 18], out += k[(v >> 12) & 63], out += "==";
  } else if (i + 2 == n) {
    const std::uint32_t v = (data[i] << 16) | (data[i + 1] << 8);
    out += k[v >> 18], out += k[(v >> 12) & 63], out += k[(v >> 6) & 63], out += '=';
  }
}

template <typename T>
const char* vtk_type() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
  if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  if constexpr (std::is_same_v<T, std::uint8_t>) return "UInt8";
}

template <typename T>
void data_array(std::string& out, const char* name, int components, const std::vector<T>& values) {
  out += msg("        <DataArray type=\"", vtk_type<T>(), "\" Name=\"", name, "\" NumberOfComponents=\"", components,
             "\" format=\"binary\">\n          ");
  const std::uint64_t bytes = values.size() * sizeof(T);
  std::vector<std::uint8_t> raw(sizeof bytes + bytes);
  std::memcpy(raw.data(), &bytes, sizeof bytes);  // little-endian on every machine dda builds for
  if (bytes) std::memcpy(raw.data() + sizeof bytes, values.data(), bytes);
  base64(raw.data(), raw.size(), out);
  out += "\n        </DataArray>\n";
}

std::string header(double time, long step, std::size_t points, std::size_t cells) {
  char t[40];
  std::snprintf(t, sizeof t, "%.17g", time);
  return msg(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "  <UnstructuredGrid>\n"
      "    <FieldData>\n"
      "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">",
      t,
      "</DataArray>\n"
      "      <DataArray type=\"Int64\" Name=\"step\" NumberOfTuples=\"1\" format=\"ascii\">",
      step,
      "</DataArray>\n"
      "    </FieldData>\n"
      "    <Piece NumberOfPoints=\"",
      points, "\" NumberOfCells=\"", cells, "\">\n");
}

void cells(std::string& out, const std::vector<double>& xyz, const std::vector<std::int64_t>& connectivity,
           const std::vector<std::int64_t>& offsets, std::uint8_t type) {
  out += "      <Points>\n";
  data_array(out, "points", 3, xyz);
  out += "      </Points>\n      <Cells>\n";
  data_array(out, "connectivity", 1, connectivity);
  data_array(out, "offsets", 1, offsets);
  data_array(out, "types", 1, std::vector<std::uint8_t>(offsets.size(), type));
  out += "      </Cells>\n";
}

const char* kFooter = "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
constexpr std::uint8_t kVtkLine = 3, kVtkPolygon = 7;

}  // namespace

std::string blocks_vtu(const World& w) {
  const std::size_t n = w.block_count();
  std::vector<double> xyz, area(n), sxx(n), syy(n), txy(n), vel(3 * n), omega(n), disp(3 * n);
  std::vector<std::int64_t> connectivity, offsets(n);
  std::vector<std::int32_t> id(n), material(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto b = static_cast<BlockId>(i);
    for (const Vec2& v : w.block_vertices(b)) {
      connectivity.push_back(static_cast<std::int64_t>(xyz.size() / 3));
      xyz.insert(xyz.end(), {v.x(), v.y(), 0.0});
    }
    offsets[i] = static_cast<std::int64_t>(connectivity.size());
    id[i] = b;
    material[i] = w.block_material(b);
    area[i] = w.block_area(b);
    const Vec3 s = w.block_stress(b);
    sxx[i] = s[0], syy[i] = s[1], txy[i] = s[2];
    const Vec6 v = w.block_velocity(b);
    vel[3 * i] = v[0], vel[3 * i + 1] = v[1], vel[3 * i + 2] = 0;
    omega[i] = v[2];
    const Vec2 u = w.block_displacement(b);
    disp[3 * i] = u.x(), disp[3 * i + 1] = u.y(), disp[3 * i + 2] = 0;
  }
  std::string out = header(w.time(), w.step_count(), xyz.size() / 3, n);
  cells(out, xyz, connectivity, offsets, kVtkPolygon);
  out += "      <CellData Scalars=\"sigma_xx\" Vectors=\"velocity\">\n";
  data_array(out, "block_id", 1, id);
  data_array(out, "material", 1, material);
  data_array(out, "area", 1, area);
  data_array(out, "sigma_xx", 1, sxx);
  data_array(out, "sigma_yy", 1, syy);
  data_array(out, "tau_xy", 1, txy);
  data_array(out, "velocity", 3, vel);
  data_array(out, "angular_velocity", 1, omega);
  data_array(out, "displacement", 3, disp);
  return out + kFooter;
}

std::string contacts_vtu(const World& w) {
  const auto& contacts = w.contacts();
  const std::size_t n = contacts.size();
  std::vector<double> xyz, fn(n), fs(n), pen(n), point(3 * n);
  std::vector<std::int64_t> connectivity(2 * n), offsets(n);
  std::vector<std::int32_t> state(n), intact(n), vblock(n), eblock(n), joint(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Contact& c = contacts[i];
    const Vec2 a = w.block_centroid(c.vblock), b = w.block_centroid(c.eblock);
    xyz.insert(xyz.end(), {a.x(), a.y(), 0.0, b.x(), b.y(), 0.0});
    connectivity[2 * i] = static_cast<std::int64_t>(2 * i);
    connectivity[2 * i + 1] = static_cast<std::int64_t>(2 * i + 1);
    offsets[i] = static_cast<std::int64_t>(2 * i + 2);
    fn[i] = c.normal_force, fs[i] = c.shear_force, pen[i] = c.penetration;
    state[i] = static_cast<std::int32_t>(c.state);
    intact[i] = c.intact ? 1 : 0;
    vblock[i] = c.vblock, eblock[i] = c.eblock, joint[i] = c.joint;
    const Vec2 p = w.block_vertices(c.vblock)[c.vertex];
    point[3 * i] = p.x(), point[3 * i + 1] = p.y(), point[3 * i + 2] = 0;
  }
  std::string out = header(w.time(), w.step_count(), 2 * n, n);
  cells(out, xyz, connectivity, offsets, kVtkLine);
  out += "      <CellData Scalars=\"normal_force\">\n";
  data_array(out, "normal_force", 1, fn);
  data_array(out, "shear_force", 1, fs);
  data_array(out, "state", 1, state);
  data_array(out, "intact", 1, intact);
  data_array(out, "penetration", 1, pen);
  data_array(out, "vblock", 1, vblock);
  data_array(out, "eblock", 1, eblock);
  data_array(out, "joint", 1, joint);
  data_array(out, "contact_point", 3, point);
  return out + kFooter;
}

// ---- series ------------------------------------------------------------------------------

VtuSeries::VtuSeries(VtuOptions o) : options_(std::move(o)) {
  if (options_.every_steps < 0 || !(options_.every_time >= 0) || !std::isfinite(options_.every_time))
    throw Error("VTU series: every and every_time must be zero or positive");
  if (options_.every_steps > 0 && options_.every_time > 0)
    throw Error("VTU series: give every or every_time, not both");
  if (options_.prefix.find('/') != std::string::npos)
    throw Error(msg("VTU series: prefix '", options_.prefix, "' must be a file name stem (no '/')"));
  std::error_code ec;
  std::filesystem::create_directories(options_.folder, ec);
  if (ec || !std::filesystem::is_directory(options_.folder, ec))
    throw Error(msg("VTU series: cannot create the folder '", options_.folder.string(), "'",
                    ec ? ": " + ec.message() : std::string()));
}

std::string VtuSeries::name(const std::string& kind) const {
  return options_.prefix.empty() ? kind : options_.prefix + "_" + kind;
}

std::filesystem::path VtuSeries::pvd(const std::string& kind) const { return options_.folder / (name(kind) + ".pvd"); }

bool VtuSeries::due(long step, double time) const {
  if (step == last_step_) return false;
  if (options_.every_steps > 0) return last_step_ < 0 || step % options_.every_steps == 0;
  if (options_.every_time > 0) return time >= next_time_ - 1e-9 * options_.every_time;
  return false;  // only on request (write())
}

void VtuSeries::maybe_write(const World& world) {
  if (due(world.step_count(), world.time())) write(world);
}

std::filesystem::path VtuSeries::write(const World& world) {
  char num[16];
  std::snprintf(num, sizeof num, "_%05d.vtu", count());
  const auto blocks = options_.folder / (name("blocks") + num);
  write_file_atomically(blocks, blocks_vtu(world));
  if (options_.contacts) write_file_atomically(options_.folder / (name("contacts") + num), contacts_vtu(world));
  times_.push_back(world.time());
  last_step_ = world.step_count();
  if (options_.every_time > 0)
    next_time_ = (std::floor(world.time() / options_.every_time + 1e-9) + 1) * options_.every_time;
  write_pvd("blocks");
  if (options_.contacts) write_pvd("contacts");
  return blocks;
}

void VtuSeries::continue_from(const World& world) {
  std::ifstream in(pvd("blocks"));
  std::string line;
  times_.clear();
  while (std::getline(in, line)) {
    const auto at = line.find("timestep=\"");
    if (at == std::string::npos) continue;
    const double t = std::strtod(line.c_str() + at + 10, nullptr);
    if (t > world.time()) break;  // written after the checkpoint by the run being continued
    times_.push_back(t);
  }
  last_step_ = world.step_count();  // its frame, if due, is among those kept
  if (options_.every_time > 0)
    next_time_ = (std::floor(world.time() / options_.every_time + 1e-9) + 1) * options_.every_time;
  write_pvd("blocks");
  if (options_.contacts) write_pvd("contacts");
}

void VtuSeries::write_pvd(const std::string& kind) const {
  std::string text =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (int i = 0; i < count(); ++i) {
    char line[256];
    std::snprintf(line, sizeof line, "    <DataSet timestep=\"%.17g\" part=\"0\" file=\"%s_%05d.vtu\"/>\n", times_[i],
                  name(kind).c_str(), i);
    text += line;
  }
  write_file_atomically(pvd(kind), text + "  </Collection>\n</VTKFile>\n");
}

}  // namespace dda::script
