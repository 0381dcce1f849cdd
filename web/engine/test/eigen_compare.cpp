// Why the engine's numbers are not bit for bit the native program's, the second reason
// (docs/javascript.md, "Same answers"): prints the bits of Eigen's results on fixed pseudo-random
// inputs (dot products, norms, sums, products, LU, QR and sparse LU solves, 2 to 30 rows, and
// fixed-size 2-vectors), one a line, for native builds with and without SSE2 and a WebAssembly
// build to be compared (EIGEN below: a folder holding only a link to /usr/include/eigen3/Eigen,
// since emscripten must not see the rest of /usr/include):
//   g++ -O3 -std=c++20 -isystem /usr/include/eigen3 eigen_compare.cpp -o sse2
//   g++ -O3 -std=c++20 -isystem /usr/include/eigen3 -DEIGEN_DONT_VECTORIZE eigen_compare.cpp -o scalar
//   em++ -O3 -std=c++20 -isystem EIGEN -sSINGLE_FILE=1 eigen_compare.cpp -o wasm.js
//   ./sse2 > sse2.txt; ./scalar > scalar.txt; node wasm.js > wasm.txt
//   diff scalar.txt wasm.txt | grep -c '^>'; diff sse2.txt wasm.txt | grep -c '^>'
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace {

void print_bits(double x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  std::printf("%016llx\n", static_cast<unsigned long long>(bits));
}

void print_bits(const Eigen::MatrixXd& m) {
  for (Eigen::Index i = 0; i < m.size(); ++i) print_bits(m.data()[i]);
}

// xorshift64: the same inputs on every platform, in [-0.5, 0.5).
class Inputs {
 public:
  double next() {
    state_ ^= state_ << 13;
    state_ ^= state_ >> 7;
    state_ ^= state_ << 17;
    return static_cast<double>(state_ >> 11) * 0x1.0p-53 - 0.5;
  }
  void fill(Eigen::MatrixXd& m) {
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = next();
  }

 private:
  std::uint64_t state_ = 88172645463325252ull;
};

}  // namespace

int main() {
  Inputs inputs;
  for (int n : {2, 3, 5, 7, 12, 30}) {
    Eigen::MatrixXd a(n, n), b(n, 3), v(n, 1), w(n, 1);
    inputs.fill(a);
    inputs.fill(b);
    inputs.fill(v);
    inputs.fill(w);
    print_bits(v.col(0).dot(w.col(0)));
    print_bits(v.norm());
    print_bits(v.sum());
    print_bits(a * b);
    print_bits(a * v);
    print_bits(a.partialPivLu().solve(b));
    print_bits(a.colPivHouseholderQr().solve(b));
    const Eigen::SparseMatrix<double> sparse = a.sparseView();
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(sparse);
    print_bits(lu.solve(b));
  }
  Eigen::Vector2d p, q;
  Eigen::Matrix2d r;
  for (double* x : {&p[0], &p[1], &q[0], &q[1], &r(0, 0), &r(0, 1), &r(1, 0), &r(1, 1)}) *x = inputs.next();
  const Eigen::Vector2d rp = r * p;
  print_bits(rp[0]);
  print_bits(rp[1]);
  print_bits(p.dot(q));
  print_bits((p - q).norm());
}
