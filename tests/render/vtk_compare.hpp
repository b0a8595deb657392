#pragma once
// Two VTK XML files compared as ParaView sees them: read back with VTK's reader, the same points,
// cells, arrays (names, types, components, every value bit for bit) and active attributes. For
// the plain XML writer's tests (render) and drumlab-mpi's VTU series against drumlab run's (mpi).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLGenericDataObjectReader.h>

namespace drumlab::test {

/// The dataset in `file` (.vtu, .vtp, .vti), or null if VTK cannot read one there.
inline vtkSmartPointer<vtkDataSet> read_back(const std::filesystem::path& file) {
  vtkNew<vtkXMLGenericDataObjectReader> r;
  r->SetFileName(file.c_str());
  r->Update();
  return vtkDataSet::SafeDownCast(r->GetOutput());
}

inline void expect_same_arrays(vtkFieldData* a, vtkFieldData* b, const char* where) {
  ASSERT_EQ(a->GetNumberOfArrays(), b->GetNumberOfArrays()) << where;
  for (int k = 0; k < a->GetNumberOfArrays(); ++k) {
    vtkDataArray* x = a->GetArray(k);
    vtkDataArray* y = b->GetArray(k);
    ASSERT_NE(x, nullptr);
    ASSERT_NE(y, nullptr);
    SCOPED_TRACE(std::string(where) + " " + x->GetName());
    EXPECT_STREQ(x->GetName(), y->GetName());
    EXPECT_EQ(x->GetDataType(), y->GetDataType());
    ASSERT_EQ(x->GetNumberOfComponents(), y->GetNumberOfComponents());
    ASSERT_EQ(x->GetNumberOfTuples(), y->GetNumberOfTuples());
    for (vtkIdType t = 0; t < x->GetNumberOfTuples(); ++t) {
      for (int c = 0; c < x->GetNumberOfComponents(); ++c) {
        ASSERT_EQ(x->GetComponent(t, c), y->GetComponent(t, c)) << "tuple " << t;
      }
    }
  }
}

inline std::string array_name(vtkDataArray* a) {
  return a ? std::string(a->GetName()) : std::string();
}

inline void expect_same_datasets(vtkDataSet* a, vtkDataSet* b) {
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  EXPECT_STREQ(a->GetClassName(), b->GetClassName());
  ASSERT_EQ(b->GetNumberOfPoints(), a->GetNumberOfPoints());
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i) {
    double p[3], q[3];
    a->GetPoint(i, p);
    b->GetPoint(i, q);
    for (int c = 0; c < 3; ++c) ASSERT_EQ(p[c], q[c]) << "point " << i;
  }
  ASSERT_EQ(b->GetNumberOfCells(), a->GetNumberOfCells());
  vtkNew<vtkIdList> ia, ib;
  for (vtkIdType k = 0; k < a->GetNumberOfCells(); ++k) {
    ASSERT_EQ(a->GetCellType(k), b->GetCellType(k)) << "cell " << k;
    a->GetCellPoints(k, ia);
    b->GetCellPoints(k, ib);
    ASSERT_EQ(ia->GetNumberOfIds(), ib->GetNumberOfIds()) << "cell " << k;
    for (vtkIdType j = 0; j < ia->GetNumberOfIds(); ++j) ASSERT_EQ(ia->GetId(j), ib->GetId(j));
  }
  expect_same_arrays(a->GetPointData(), b->GetPointData(), "point data");
  expect_same_arrays(a->GetCellData(), b->GetCellData(), "cell data");
  expect_same_arrays(a->GetFieldData(), b->GetFieldData(), "field data");
  EXPECT_EQ(array_name(a->GetPointData()->GetScalars()),
            array_name(b->GetPointData()->GetScalars()));
  EXPECT_EQ(array_name(a->GetPointData()->GetVectors()),
            array_name(b->GetPointData()->GetVectors()));
  EXPECT_EQ(array_name(a->GetCellData()->GetScalars()), array_name(b->GetCellData()->GetScalars()));
}

}  // namespace drumlab::test
