// The .pvd time series and history.csv: small text files kept in memory and rewritten
// whole (atomically) so that a reader never sees a partial file.
#include <string>

#include "io/text_format.hpp"
#include "stagger/output.hpp"
#include "stagger/simulation.hpp"

namespace stagger {

PvdWriter::PvdWriter(std::string pvd_path) : path_(std::move(pvd_path)) {}

void PvdWriter::add(double time, const std::string& vtu_file) {
  entries_.emplace_back(time, vtu_file);
  if (!path_.empty()) write();  // no path: kept in memory only (a distributed run's other ranks)
}

void PvdWriter::mark_last_good_state(const std::string& why) {
  // "--" may not appear inside an XML comment.
  std::string note;
  for (const char c : why) note += (c == '-' && !note.empty() && note.back() == '-') ? ' ' : c;
  last_good_note_ = note;
  if (!path_.empty()) write();
}

void PvdWriter::write() const {
  // ParaView's Collection format (VTK has no writer for it): one DataSet per dump.
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& [t, file] : entries_) {
    text += "    <DataSet timestep=\"" + io_detail::format_double(t) + "\" group=\"\" part=\"0\" file=\"" +
            io_detail::xml_attribute(file) + "\"/>\n";
  }
  if (!last_good_note_.empty() && !entries_.empty())
    text += "    <!-- last good state: the run stopped after this dump: " + io_detail::xml_attribute(last_good_note_) +
            " -->\n";
  text += "  </Collection>\n</VTKFile>\n";
  write_file_atomically(path_, text);
}

namespace {
constexpr const char* history_header =
    "time,cycle,dt,kinetic,internal,boundary_work,source_work,total,relative_energy_error,momentum_x,"
    "momentum_y,ale_fixup\n";
}

HistoryWriter::HistoryWriter(std::string csv_path) : path_(std::move(csv_path)), rows_(history_header) {}

void HistoryWriter::record(const Simulation& simulation) {
  const EnergyAudit energy = simulation.energy();
  const auto momentum = simulation.momentum();
  using io_detail::format_double;
  rows_ += format_double(simulation.time());
  rows_ += ',' + std::to_string(simulation.cycle());
  for (const double value : {simulation.dt(), energy.kinetic, energy.internal, energy.boundary_work, energy.source_work,
                             energy.total, energy.relative_error, momentum[0], momentum[1], energy.ale_fixup}) {
    rows_ += ',';
    rows_ += format_double(value);
  }
  rows_ += '\n';
}

void HistoryWriter::flush() const {
  if (path_.empty()) return;  // kept in memory only (a distributed run's other ranks)
  write_file_atomically(path_, rows_);
}

}  // namespace stagger
