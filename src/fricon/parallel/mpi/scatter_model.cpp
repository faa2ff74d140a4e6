#include "fricon/parallel/mpi/scatter_model.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "fricon/core/error.hpp"
#include "fricon/parallel/mpi/partition.hpp"
#include "fricon/parallel/mpi/session.hpp"
#include "fricon/parallel/mpi/test_fault.hpp"

namespace fricon::parallel {

namespace {

// A part of the model as bytes: each array as its length and its elements.
class Writer {
 public:
  template <class T>
  void put(const T* data, std::size_t n) {
    static_assert(std::is_trivially_copyable_v<T>);
    put_raw(&n, sizeof n);
    put_raw(data, n * sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& v) {
    put(v.data(), v.size());
  }
  template <class Matrix>
  void put_matrix(const Matrix& m) {  // the rows are known (3 or 4): the columns and the data
    put(m.data(), static_cast<std::size_t>(m.size()));
  }
  template <class Matrix>
  void put_rows_and_matrix(const Matrix& m) {  // a matrix of run-time rows (the extra nodes)
    const std::size_t rows = static_cast<std::size_t>(m.rows());
    put_raw(&rows, sizeof rows);
    put(m.data(), static_cast<std::size_t>(m.size()));
  }
  void put(const std::vector<std::string>& names) {
    const std::size_t n = names.size();
    put_raw(&n, sizeof n);
    for (const std::string& s : names)
      put(s.data(), s.size());
  }
  std::vector<char> bytes;

 private:
  void put_raw(const void* data, std::size_t n) {
    const char* p = static_cast<const char*>(data);
    bytes.insert(bytes.end(), p, p + n);
  }
};

class Reader {
 public:
  explicit Reader(const std::vector<char>& bytes) : bytes_(bytes) {}
  template <class T>
  std::vector<T> get() {
    const std::size_t n = count();
    std::vector<T> v(n);
    get_raw(v.data(), n * sizeof(T));
    return v;
  }
  template <class Matrix>
  void get_rows_and_matrix(Matrix& m) {
    std::size_t rows = 0;
    get_raw(&rows, sizeof rows);
    const std::size_t n = count();
    FRICON_CHECK(rows == 0 ? n == 0 : n % rows == 0,
                 "a part of the model: " << n << " entries in " << rows << " rows");
    m.resize(static_cast<Index>(rows), rows == 0 ? 0 : static_cast<Index>(n / rows));
    get_raw(m.data(), n * sizeof(typename Matrix::Scalar));
  }
  template <class Matrix>
  void get_matrix(Matrix& m) {
    const std::size_t n = count();
    FRICON_CHECK(n % static_cast<std::size_t>(m.RowsAtCompileTime) == 0,
                 "a part of the model: an array of " << n << " entries");
    m.resize(m.RowsAtCompileTime, static_cast<Index>(n) / m.RowsAtCompileTime);
    get_raw(m.data(), n * sizeof(typename Matrix::Scalar));
  }
  std::vector<std::string> get_names() {
    std::vector<std::string> names(count());
    for (std::string& s : names) {
      const std::vector<char> c = get<char>();
      s.assign(c.begin(), c.end());
    }
    return names;
  }
  bool at_end() const { return position_ == bytes_.size(); }

 private:
  std::size_t count() {
    std::size_t n = 0;
    get_raw(&n, sizeof n);
    return n;
  }
  void get_raw(void* data, std::size_t n) {
    FRICON_CHECK(position_ + n <= bytes_.size(), "a part of the model ends early");
    std::memcpy(data, bytes_.data() + position_, n);
    position_ += n;
  }
  const std::vector<char>& bytes_;
  std::size_t position_ = 0;
};

std::vector<char> pack(const driver::ModelPart& part) {
  const mesh::TetMesh& m = part.model.mesh;
  const fe::DofMap& dofs = part.model.dofs;
  std::vector<char> fixed(static_cast<std::size_t>(3 * m.n_nodes()));
  for (Index a = 0; a < m.n_nodes(); ++a)
    for (int c = 0; c < 3; ++c)
      fixed[static_cast<std::size_t>(3 * a + c)] = dofs.is_fixed(a, c) ? 1 : 0;
  Writer w;
  w.put_matrix(m.nodes);
  w.put_matrix(m.tets);
  w.put_matrix(m.faces);
  w.put_rows_and_matrix(m.tet_extra);
  w.put_rows_and_matrix(m.face_extra);
  w.put(m.face_tag);
  w.put(m.tag_names);
  w.put(m.face_entity);
  w.put(m.tet_region);
  w.put(m.region_names);
  w.put(fixed);
  w.put_matrix(part.model.prescribed);
  w.put(part.global_dof);
  return std::move(w.bytes);
}

driver::ModelPart unpack(const std::vector<char>& bytes) {
  driver::ModelPart part;
  mesh::TetMesh& m = part.model.mesh;
  Reader r(bytes);
  r.get_matrix(m.nodes);
  r.get_matrix(m.tets);
  r.get_matrix(m.faces);
  r.get_rows_and_matrix(m.tet_extra);
  r.get_rows_and_matrix(m.face_extra);
  m.face_tag = r.get<int>();
  m.tag_names = r.get_names();
  m.face_entity = r.get<int>();
  m.tet_region = r.get<int>();
  m.region_names = r.get_names();
  const std::vector<char> fixed = r.get<char>();
  r.get_matrix(part.model.prescribed);
  part.global_dof = r.get<Index>();
  FRICON_CHECK(r.at_end(), "a part of the model has bytes left over");
  part.model.dofs =
      driver::part_dofs(std::vector<bool>(fixed.begin(), fixed.end()), part.global_dof);
  return part;
}

// A message's length, or this instead when rank 0 failed to build the part.
constexpr long kFailed = -1;
// Bytes per message: MPI counts are int.
constexpr std::size_t kChunk = std::size_t{1} << 30;
constexpr int kTag = 7301;

// What a failed MPI call was part of, for its message (check_mpi).
constexpr const char* kScattering = "giving the ranks their parts of the model";

void send(const std::vector<char>& bytes, int to, MPI_Comm comm) {
  long n = static_cast<long>(bytes.size());
  check_mpi(MPI_Send(&n, 1, MPI_LONG, to, kTag, comm), "MPI_Send", kScattering);
  for (std::size_t at = 0; at < bytes.size(); at += kChunk)
    check_mpi(MPI_Send(bytes.data() + at, static_cast<int>(std::min(kChunk, bytes.size() - at)),
                       MPI_BYTE, to, kTag, comm),
              "MPI_Send", kScattering);
}

// This rank's part from rank 0, or nothing when rank 0 failed to build it.
std::optional<std::vector<char>> receive(MPI_Comm comm) {
  long n = 0;
  check_mpi(MPI_Recv(&n, 1, MPI_LONG, 0, kTag, comm, MPI_STATUS_IGNORE), "MPI_Recv", kScattering);
  if (n == kFailed) return std::nullopt;
  test_fault("scatter");
  std::vector<char> bytes(static_cast<std::size_t>(n));
  for (std::size_t at = 0; at < bytes.size(); at += kChunk)
    check_mpi(MPI_Recv(bytes.data() + at, static_cast<int>(std::min(kChunk, bytes.size() - at)),
                       MPI_BYTE, 0, kTag, comm, MPI_STATUS_IGNORE),
              "MPI_Recv", kScattering);
  return bytes;
}

}  // namespace

driver::ModelPart scatter_model(const driver::Problem& problem, const driver::Model* whole,
                                const std::vector<int>& owner, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (rank != 0) {
    // Rank 0 sends the part once this rank has its length: a failure of this rank alone before
    // the part has arrived leaves rank 0 waiting in MPI_Send, and ends the job (or_abort); after,
    // it is the caller's to agree on (collectively).
    std::optional<std::vector<char>> bytes;
    or_abort([&] { bytes = receive(comm); }, comm);
    if (!bytes) throw Error("rank 0 could not give this rank its part of the model");
    driver::ModelPart part = unpack(*bytes);
    part.model.materials = driver::make_materials(problem, part.model.mesh);
    return part;
  }
  // Rank 0: the other ranks' parts one at a time, then its own.
  std::vector<std::vector<Index>> elements;
  int to = 1;
  try {
    elements = elements_by_rank(owner, size);
    for (; to < size; ++to) {
      auto& theirs = elements[static_cast<std::size_t>(to)];
      send(pack(driver::model_part(*whole, theirs)), to, comm);
      std::vector<Index>().swap(theirs);  // sent: free it
    }
  } catch (...) {
    const long failed = kFailed;  // to the ranks still waiting for their part
    for (; to < size; ++to)
      MPI_Send(&failed, 1, MPI_LONG, to, kTag, comm);
    throw;
  }
  return driver::model_part(*whole, elements[0]);
}

}  // namespace fricon::parallel
