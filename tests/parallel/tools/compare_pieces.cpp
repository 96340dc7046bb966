// compare_pieces SERIAL.vtu PARALLEL.pvtu RANKS: a distributed run's dump (a .pvtu and its
// per-rank pieces, docs/output.md) holds the serial dump's state bit for bit. Reads both with
// VTK's own readers (so the .pvtu must be valid), then matches zones by `zone_id` and points
// by `point_id` (the serial numbers): every zone exactly once, its points in the same order,
// every array of the serial file with the same bits, `rank` in [0, RANKS), the time and cycle.
// Exit status 0 when identical; the first differences are printed.
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

int failures = 0;

void fail(const std::string& what) {
  if (++failures <= 10) std::fprintf(stderr, "compare_pieces: %s\n", what.c_str());
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

vtkIntArray* int_array(vtkDataSetAttributes* data, const char* name) {
  auto* array = vtkIntArray::SafeDownCast(data->GetAbstractArray(name));
  if (!array) fail(std::string("the pieces have no int array '") + name + "'");
  return array;
}

// Every array of `serial` against `pieces`, tuple t of the serial one against tuple map[t].
void compare_arrays(vtkDataSetAttributes* serial, vtkDataSetAttributes* pieces, const std::vector<vtkIdType>& map,
                    const char* what) {
  for (int i = 0; i < serial->GetNumberOfArrays(); ++i) {
    vtkDataArray* a = serial->GetArray(i);
    vtkDataArray* b = pieces->GetArray(a->GetName());
    if (!b || b->GetNumberOfComponents() != a->GetNumberOfComponents() || b->GetDataType() != a->GetDataType()) {
      fail(std::string(what) + " array '" + a->GetName() + "' is missing from the pieces or differs in type");
      continue;
    }
    for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
      for (int c = 0; c < a->GetNumberOfComponents(); ++c)
        if (!same_bits(a->GetComponent(t, c), b->GetComponent(map[t], c)))
          fail(std::string(what) + " " + std::to_string(t) + ": '" + a->GetName() + "' differs");
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: compare_pieces SERIAL.vtu PARALLEL.pvtu RANKS\n");
    return 2;
  }
  const int ranks = std::atoi(argv[3]);
  vtkNew<vtkXMLUnstructuredGridReader> serial_reader;
  serial_reader->SetFileName(argv[1]);
  serial_reader->Update();
  vtkNew<vtkXMLPUnstructuredGridReader> piece_reader;
  piece_reader->SetFileName(argv[2]);
  piece_reader->Update();
  vtkUnstructuredGrid* s = serial_reader->GetOutput();
  vtkUnstructuredGrid* p = piece_reader->GetOutput();
  if (s->GetNumberOfCells() == 0 || p->GetNumberOfCells() != s->GetNumberOfCells()) {
    std::fprintf(stderr, "compare_pieces: %s has %lld zones, %s %lld\n", argv[1],
                 static_cast<long long>(s->GetNumberOfCells()), argv[2], static_cast<long long>(p->GetNumberOfCells()));
    return 1;
  }
  vtkIntArray* zone_id = int_array(p->GetCellData(), "zone_id");
  vtkIntArray* point_id = int_array(p->GetPointData(), "point_id");
  vtkIntArray* rank = int_array(p->GetCellData(), "rank");
  if (!zone_id || !point_id || !rank) return 1;

  // Zones: each serial zone once; the same points (by serial number) in the same order.
  const vtkIdType nz = s->GetNumberOfCells(), np = s->GetNumberOfPoints();
  std::vector<vtkIdType> zone_map(nz, -1), point_map(np, -1);
  std::vector<int> used_ranks(ranks > 0 ? ranks : 1, 0);
  for (vtkIdType c = 0; c < nz; ++c) {
    const int z = zone_id->GetValue(c), r = rank->GetValue(c);
    if (z < 0 || z >= nz || zone_map[z] >= 0) {
      fail("zone_id " + std::to_string(z) + " is out of range or appears twice");
      continue;
    }
    zone_map[z] = c;
    if (r < 0 || r >= ranks)
      fail("zone " + std::to_string(z) + " has rank " + std::to_string(r));
    else
      used_ranks[r] = 1;
  }
  for (int r = 0; r < ranks; ++r)
    if (!used_ranks[r]) fail("no zone has rank " + std::to_string(r));
  vtkNew<vtkIdList> a, b;
  for (vtkIdType z = 0; z < nz && failures == 0; ++z) {
    s->GetCellPoints(z, a);
    p->GetCellPoints(zone_map[z], b);
    if (a->GetNumberOfIds() != b->GetNumberOfIds() || s->GetCellType(z) != p->GetCellType(zone_map[z])) {
      fail("zone " + std::to_string(z) + " differs in shape");
      continue;
    }
    for (vtkIdType k = 0; k < a->GetNumberOfIds(); ++k) {
      const vtkIdType q = b->GetId(k);
      if (point_id->GetValue(q) != a->GetId(k)) fail("zone " + std::to_string(z) + " has other points");
      // A point shared by pieces appears in each: all its copies must be equal (checked below).
      if (point_map[a->GetId(k)] < 0) point_map[a->GetId(k)] = q;
      double xa[3], xb[3];
      s->GetPoint(a->GetId(k), xa);
      p->GetPoint(q, xb);
      for (int d = 0; d < 3; ++d)
        if (!same_bits(xa[d], xb[d])) fail("point " + std::to_string(a->GetId(k)) + " is elsewhere");
    }
  }
  for (vtkIdType q = 0; q < np; ++q)
    if (point_map[q] < 0) fail("point " + std::to_string(q) + " is in no piece");
  if (failures == 0) {
    compare_arrays(s->GetCellData(), p->GetCellData(), zone_map, "zone");
    compare_arrays(s->GetPointData(), p->GetPointData(), point_map, "point");
    // Every copy of a shared point carries the same velocity as the serial point.
    for (vtkIdType q = 0; q < p->GetNumberOfPoints(); ++q) {
      const vtkIdType serial = point_id->GetValue(q);
      for (int i = 0; i < s->GetPointData()->GetNumberOfArrays(); ++i) {
        vtkDataArray* x = s->GetPointData()->GetArray(i);
        vtkDataArray* y = p->GetPointData()->GetArray(x->GetName());
        for (int c = 0; y && c < x->GetNumberOfComponents(); ++c)
          if (!same_bits(x->GetComponent(serial, c), y->GetComponent(q, c)))
            fail("a copy of point " + std::to_string(serial) + " differs in '" + x->GetName() + "'");
      }
    }
  }
  // The time and the cycle (the pieces' field data; the reader keeps the first piece's).
  for (const char* name : {"TimeValue", "cycle"}) {
    vtkDataArray* x = s->GetFieldData()->GetArray(name);
    vtkDataArray* y = p->GetFieldData()->GetArray(name);
    if (!x || !y || !same_bits(x->GetComponent(0, 0), y->GetComponent(0, 0)))
      fail(std::string("field '") + name + "' differs");
  }
  if (failures > 0) {
    std::fprintf(stderr, "compare_pieces: %s and %s differ (%d differences)\n", argv[1], argv[2], failures);
    return 1;
  }
  return 0;
}
