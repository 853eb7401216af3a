#include "sampling/sobol.h"

#include <array>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include "common/paths.h"

namespace wb {
namespace {

// Multiplicative order of x modulo the degree-s polynomial `poly` (bit i = coefficient of x^i), or 0 if x^k
// never returns to 1 within 2^s - 1 steps.
uint32_t orderOfX(uint32_t poly, int s) {
  uint32_t period = (1u << s) - 1u;
  uint32_t v = 1u;
  for (uint32_t k = 1; k <= period; ++k) {
    v <<= 1;
    if (v & (1u << s)) v ^= poly;
    if (v == 1u) return k;
  }
  return 0;
}

// Direction numbers V_1..V_32 of one dimension from its polynomial and initial m values.
std::array<uint32_t, 32> directions(const SobolPolynomial& p, const std::vector<uint32_t>& mInit) {
  int s = p.degree;
  std::array<uint32_t, 33> m{};
  for (int i = 1; i <= s && i <= 32; ++i) m[i] = mInit[i - 1];
  for (int i = s + 1; i <= 32; ++i) {
    uint32_t v = m[i - s] ^ (m[i - s] << s);
    for (int k = 1; k < s; ++k) {
      if ((p.a >> (s - 1 - k)) & 1u) v ^= m[i - k] << k;
    }
    m[i] = v;
  }
  std::array<uint32_t, 32> out{};
  for (int i = 1; i <= 32; ++i) out[i - 1] = m[i] << (32 - i);  // m_i < 2^i, so this keeps every bit
  return out;
}

uint32_t hash32(uint32_t v) {
  uint32_t state = v * 747796405u + 2891336453u;
  uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Rank (over GF(2)) of up to 32 row vectors.
int rankGF2(std::vector<uint32_t> rows) {
  int rank = 0;
  for (int bit = 31; bit >= 0 && rank < static_cast<int>(rows.size()); --bit) {
    uint32_t mask = 1u << bit;
    int pivot = -1;
    for (int r = rank; r < static_cast<int>(rows.size()); ++r) {
      if (rows[r] & mask) {
        pivot = r;
        break;
      }
    }
    if (pivot < 0) continue;
    std::swap(rows[rank], rows[pivot]);
    for (int r = 0; r < static_cast<int>(rows.size()); ++r) {
      if (r != rank && (rows[r] & mask)) rows[r] ^= rows[rank];
    }
    ++rank;
  }
  return rank;
}

// Generator-matrix rows of one dimension for m columns: row r = bit (31 - r) of V_1..V_m.
std::vector<uint32_t> matrixRows(const uint32_t* v, int m) {
  std::vector<uint32_t> rows(m, 0u);
  for (int r = 0; r < m; ++r) {
    for (int k = 0; k < m; ++k) rows[r] |= ((v[k] >> (31 - r)) & 1u) << k;
  }
  return rows;
}

int pairTValue(const uint32_t* va, const uint32_t* vb, int m) {
  std::vector<uint32_t> ra = matrixRows(va, m);
  std::vector<uint32_t> rb = matrixRows(vb, m);
  for (int t = 0; t <= m; ++t) {
    bool ok = true;
    int q = m - t;
    for (int d1 = 0; d1 <= q && ok; ++d1) {
      std::vector<uint32_t> rows(ra.begin(), ra.begin() + d1);
      rows.insert(rows.end(), rb.begin(), rb.begin() + (q - d1));
      ok = rankGF2(rows) == q;
    }
    if (ok) return t;
  }
  return m;
}

// Dimensions whose 2D projections with `dim` matter most: the pixel dims and the dims of the same bounce
// (layout of shaders/shared/random.h: 2 + 10 * bounce + k).
std::vector<int> partners(int dim) {
  std::vector<int> out;
  if (dim < 2) {
    for (int d = 0; d < dim; ++d) out.push_back(d);
    return out;
  }
  out = {0, 1};
  int base = 2 + ((dim - 2) / 10) * 10;
  for (int d = base; d < dim; ++d) out.push_back(d);
  if (base >= 12) {
    for (int k = 0; k < 3; ++k) out.push_back(base - 10 + k);  // previous bounce's BRDF dims
  }
  return out;
}

std::vector<uint32_t> generate(int dims) {
  std::vector<SobolPolynomial> polys = primitivePolynomials(dims > 1 ? dims - 1 : 0);
  std::vector<uint32_t> out(static_cast<size_t>(dims) * 32u, 0u);
  for (int bit = 0; bit < 32 && dims > 0; ++bit) out[bit] = 1u << (31 - bit);
  constexpr int kCandidates = 24;
  constexpr int kMaxM = 10;
  for (int dim = 1; dim < dims; ++dim) {
    const SobolPolynomial& p = polys[dim - 1];
    std::vector<int> with = partners(dim);
    std::array<uint32_t, 32> best{};
    int bestScore = -1;
    for (int c = 0; c < kCandidates; ++c) {
      std::vector<uint32_t> mInit(p.degree);
      for (int k = 1; k <= p.degree; ++k) {
        // Odd, below 2^k. Candidate 0 is all ones (the classical choice for dim 1).
        uint32_t r = c == 0 ? 1u : hash32(static_cast<uint32_t>(dim * 7919 + c * 104729 + k));
        mInit[k - 1] = (r & ((1u << k) - 1u)) | 1u;
      }
      std::array<uint32_t, 32> v = directions(p, mInit);
      int score = 0;
      for (int other : with) {
        for (int m = 2; m <= kMaxM; ++m) {
          int t = pairTValue(v.data(), &out[static_cast<size_t>(other) * 32u], m);
          score += t * t;
        }
      }
      if (bestScore < 0 || score < bestScore) {
        bestScore = score;
        best = v;
      }
      if (p.degree == 1) break;  // m_1 = 1 is the only choice
    }
    for (int bit = 0; bit < 32; ++bit) out[static_cast<size_t>(dim) * 32u + bit] = best[bit];
  }
  return out;
}

}  // namespace

std::vector<SobolPolynomial> primitivePolynomials(int count) {
  std::vector<SobolPolynomial> out;
  for (int s = 1; static_cast<int>(out.size()) < count; ++s) {
    if (s > 24) throw std::runtime_error("primitivePolynomials: too many polynomials requested");
    // 2^s - 1 as an order check: x has order exactly 2^s - 1 iff the polynomial is primitive.
    for (uint32_t a = 0; a < (1u << (s - 1)) && static_cast<int>(out.size()) < count; ++a) {
      uint32_t poly = (1u << s) | (a << 1) | 1u;
      if (orderOfX(poly, s) == (1u << s) - 1u) out.push_back({s, a});
    }
  }
  return out;
}

std::vector<uint32_t> generateSobolDirectionNumbers(int dims) {
  if (dims < 0 || dims > 4096)
    throw std::invalid_argument("generateSobolDirectionNumbers: dims out of range");
  return generate(dims);
}

std::filesystem::path sobolCommittedPath() {
  return assetDir() / "sampling" / "sobol_dirs.bin";
}

std::vector<uint32_t> loadCommittedSobolDirections() {
  const std::filesystem::path path = sobolCommittedPath();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("sobolDirectionNumbers: cannot open " + path.string());
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t expected = static_cast<size_t>(kSobolCommittedDims) * 32u * 4u;
  if (bytes.size() != expected) {
    throw std::runtime_error("sobolDirectionNumbers: " + path.string() + " has " +
                             std::to_string(bytes.size()) + " bytes, expected " + std::to_string(expected) +
                             " (regenerate it with wb_gen_sobol)");
  }
  std::vector<uint32_t> out(expected / 4u);
  for (size_t i = 0; i < out.size(); ++i) {
    out[i] = static_cast<uint32_t>(bytes[4 * i]) | (static_cast<uint32_t>(bytes[4 * i + 1]) << 8) |
             (static_cast<uint32_t>(bytes[4 * i + 2]) << 16) |
             (static_cast<uint32_t>(bytes[4 * i + 3]) << 24);
  }
  return out;
}

std::vector<uint32_t> sobolDirectionNumbers(int dims) {
  if (dims < 0 || dims > 4096) throw std::invalid_argument("sobolDirectionNumbers: dims out of range");
  static std::mutex mutex;
  static std::map<int, std::vector<uint32_t>> cache;
  static std::vector<uint32_t> committed;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(dims);
  if (it != cache.end()) return it->second;
  std::vector<uint32_t> result;
  if (dims <= kSobolCommittedDims) {
    if (committed.empty()) committed = loadCommittedSobolDirections();
    result.assign(committed.begin(), committed.begin() + static_cast<ptrdiff_t>(dims) * 32);
  } else {
    result = generate(dims);  // beyond the committed table: the (slow) search
  }
  return cache.emplace(dims, std::move(result)).first->second;
}

int sobolPairTValue(const std::vector<uint32_t>& dirs, int dimA, int dimB, int m) {
  return pairTValue(&dirs[static_cast<size_t>(dimA) * 32u], &dirs[static_cast<size_t>(dimB) * 32u], m);
}

}  // namespace wb
