#include "io/RunDeflate.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cstring>
#include <vector>

#include <libdeflate.h>

namespace frugal {

namespace {

// RFC 1951 section 3.2.5: the length codes 257..285, their base lengths and extra bits.
constexpr std::array<std::uint16_t, 29> kLengthBase = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                                       31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::array<std::uint8_t, 29> kLengthExtra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                       2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
// The order in which the code-length code's lengths are stored (section 3.2.7).
constexpr std::array<std::uint8_t, 19> kCodeLengthOrder = {16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                                           11, 4,  12, 3, 13, 2, 14, 1, 15};
constexpr int kLitLenCodes = 286, kDistCodes = 30, kCodeLengthCodes = 19;
constexpr std::size_t kBlockInput = std::size_t(1) << 18;  // bytes of input per block: codes adapt per region
// The shortest run taken as a match: a match of 3 costs about what 3 literals of small residuals
// do (measured at 1080p: 4 gives files 1-5 % smaller than 3, 6 larger again).
constexpr std::size_t kMinRun = 4;

// The length code (0..28, for symbol 257 + code) of each match length 3..258.
constexpr std::array<std::uint8_t, 259> kLengthCode = [] {
    std::array<std::uint8_t, 259> table{};
    for (int code = 0; code < 29; ++code) {
        const int last = code == 28 ? 258 : (code == 27 ? 257 : kLengthBase[code + 1] - 1);
        for (int length = kLengthBase[code]; length <= last; ++length) table[length] = std::uint8_t(code);
    }
    return table;
}();

// Huffman code lengths for `freq` (n symbols), none longer than `maxBits`: Huffman's tree by the
// two-queue method; when it is too deep, the frequencies are flattened (halved, at least 1) and
// the tree built again. The code is complete: a lone symbol gets a partner of length 1, since
// decoders refuse an incomplete code-length code.
void huffmanLengths(const std::uint32_t* freq, int n, int maxBits, std::uint8_t* lengths) {
    std::fill(lengths, lengths + n, std::uint8_t(0));
    std::vector<int> symbols;
    for (int s = 0; s < n; ++s)
        if (freq[s] > 0) symbols.push_back(s);
    const int m = int(symbols.size());
    if (m == 0) return;
    if (m == 1) {
        lengths[symbols[0]] = 1;
        lengths[symbols[0] == 0 ? 1 : 0] = 1;
        return;
    }
    std::vector<std::uint64_t> weight(std::size_t(2 * m));
    std::vector<int> parent(std::size_t(2 * m)), depth(std::size_t(2 * m));
    std::vector<std::uint32_t> f(freq, freq + n);
    for (;;) {
        std::sort(symbols.begin(), symbols.end(), [&](int a, int b) {
            return f[std::size_t(a)] != f[std::size_t(b)] ? f[std::size_t(a)] < f[std::size_t(b)] : a < b;
        });
        for (int i = 0; i < m; ++i) weight[std::size_t(i)] = f[std::size_t(symbols[std::size_t(i)])];
        int leaf = 0, inner = m;
        const auto smallest = [&](int next) {
            if (leaf < m && (inner >= next || weight[std::size_t(leaf)] <= weight[std::size_t(inner)])) return leaf++;
            return inner++;
        };
        for (int next = m; next < 2 * m - 1; ++next) {
            const int a = smallest(next), b = smallest(next);
            weight[std::size_t(next)] = weight[std::size_t(a)] + weight[std::size_t(b)];
            parent[std::size_t(a)] = parent[std::size_t(b)] = next;
        }
        depth[std::size_t(2 * m - 2)] = 0;
        int deepest = 0;
        for (int node = 2 * m - 3; node >= 0; --node) {
            depth[std::size_t(node)] = depth[std::size_t(parent[std::size_t(node)])] + 1;
            if (node < m) deepest = std::max(deepest, depth[std::size_t(node)]);
        }
        if (deepest <= maxBits) {
            for (int i = 0; i < m; ++i) lengths[symbols[std::size_t(i)]] = std::uint8_t(depth[std::size_t(i)]);
            return;
        }
        for (std::uint32_t& v : f)
            if (v > 0) v = (v >> 1) | 1u;
    }
}

// Canonical codes for `lengths` (section 3.2.2), bit-reversed: deflate sends a Huffman code's
// most significant bit first into a stream filled from the least significant bit.
void canonicalCodes(const std::uint8_t* lengths, int n, std::uint16_t* codes) {
    std::array<int, 16> count{};
    for (int s = 0; s < n; ++s) ++count[lengths[s]];
    count[0] = 0;
    std::array<int, 16> next{};
    int code = 0;
    for (int bits = 1; bits < 16; ++bits) {
        code = (code + count[std::size_t(bits - 1)]) << 1;
        next[std::size_t(bits)] = code;
    }
    for (int s = 0; s < n; ++s) {
        const int length = lengths[s];
        if (length == 0) {
            codes[s] = 0;
            continue;
        }
        int value = next[std::size_t(length)]++, reversed = 0;
        for (int b = 0; b < length; ++b, value >>= 1) reversed = (reversed << 1) | (value & 1);
        codes[s] = std::uint16_t(reversed);
    }
}

// Bits into a buffer sized beforehand, least significant first.
class BitWriter {
public:
    explicit BitWriter(std::uint8_t* at) : at_(at) {}
    void put(std::uint32_t value, int bits) {
        buffer_ |= std::uint64_t(value) << count_;
        count_ += bits;
        if (count_ >= 32) {
            for (int k = 0; k < 4; ++k) *at_++ = std::uint8_t(buffer_ >> (8 * k));
            buffer_ >>= 32;
            count_ -= 32;
        }
    }
    // Pads to a whole byte and writes out what is pending.
    void align() {
        while (count_ > 0) {
            *at_++ = std::uint8_t(buffer_);
            buffer_ >>= 8;
            count_ = std::max(0, count_ - 8);
        }
        buffer_ = 0;
    }
    void bytes(const std::uint8_t* data, std::size_t size) {
        assert(count_ == 0);
        if (size == 0) return;  // an empty input may come as a null pointer
        std::memcpy(at_, data, size);
        at_ += size;
    }
    std::uint8_t* position() const { return at_; }

private:
    std::uint8_t* at_;
    std::uint64_t buffer_ = 0;
    int count_ = 0;
};

// A block's symbols: a literal byte (0..255) or a match of length 3..258 (256 + length - 3).
struct Block {
    std::vector<std::uint16_t> tokens;
    std::array<std::uint32_t, kLitLenCodes> freq{};
    std::uint64_t extraBits = 0;  // the length codes' extra bits
    std::size_t matches = 0;
    void clear() {
        tokens.clear();
        freq.fill(0);
        extraBits = 0;
        matches = 0;
    }
    void literal(std::uint8_t byte) {
        tokens.push_back(byte);
        ++freq[byte];
    }
    void match(std::size_t length) {
        tokens.push_back(std::uint16_t(256 + length - 3));
        const int code = kLengthCode[length];
        ++freq[std::size_t(257 + code)];
        extraBits += kLengthExtra[std::size_t(code)];
        ++matches;
    }
};

// Stored blocks of `size` bytes (at most 65,535 each).
std::uint64_t storedBits(std::size_t size, bool) {
    const std::uint64_t pieces = std::max<std::uint64_t>(1, (size + 65534) / 65535);
    return pieces * (3 + 7 + 32) + 8 * std::uint64_t(size);
}

void writeStored(BitWriter& out, const std::uint8_t* data, std::size_t size, bool final) {
    std::size_t at = 0;
    do {
        const std::size_t piece = std::min<std::size_t>(65535, size - at);
        const bool last = final && at + piece == size;
        out.put(last ? 1u : 0u, 1);
        out.put(0, 2);  // stored
        out.align();
        const std::uint8_t header[4] = {std::uint8_t(piece), std::uint8_t(piece >> 8), std::uint8_t(~piece),
                                        std::uint8_t(~piece >> 8)};
        out.bytes(header, 4);
        out.bytes(data + at, piece);
        at += piece;
    } while (at < size);
}

// RFC 1951 section 3.2.5: a distance's code (0..29) and its extra bits.
struct Distance {
    int code = 0, extraBits = 0;
    std::uint32_t extra = 0;
};
Distance distanceOf(std::size_t distance) {
    static constexpr std::array<std::uint16_t, 30> kBase = {
        1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
        193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
    int code = 29;
    while (kBase[std::size_t(code)] > distance) --code;
    const int extraBits = code < 4 ? 0 : code / 2 - 1;
    return {code, extraBits, std::uint32_t(distance - kBase[std::size_t(code)])};
}

// The block as a dynamic Huffman block, or stored when that is smaller.
void writeBlock(BitWriter& out, Block& block, const std::uint8_t* input, std::size_t inputSize, std::size_t step,
                bool final) {
    block.freq[256] = 1;  // end of block
    std::array<std::uint8_t, kLitLenCodes> litLengths{};
    huffmanLengths(block.freq.data(), kLitLenCodes, 15, litLengths.data());
    // The one distance used, and a partner: two codes of one bit, a complete code (decoders differ
    // on incomplete ones).
    const Distance distance = distanceOf(step);
    std::array<std::uint8_t, kDistCodes> distLengths{};
    distLengths[std::size_t(distance.code)] = 1;
    distLengths[distance.code == 0 ? 1 : 0] = 1;

    int hlit = kLitLenCodes;
    while (hlit > 257 && litLengths[std::size_t(hlit - 1)] == 0) --hlit;
    int hdist = kDistCodes;
    while (hdist > 1 && distLengths[std::size_t(hdist - 1)] == 0) --hdist;

    // The two code-length sequences as one, run-length coded with symbols 16 (repeat the last 3-6
    // times), 17 (3-10 zeros) and 18 (11-138 zeros).
    std::array<std::uint8_t, kLitLenCodes + kDistCodes> all{};
    std::copy(litLengths.begin(), litLengths.begin() + hlit, all.begin());
    std::copy(distLengths.begin(), distLengths.begin() + hdist, all.begin() + hlit);
    const int total = hlit + hdist;
    struct Code {
        std::uint8_t symbol, extra;
    };
    std::vector<Code> codes;
    std::array<std::uint32_t, kCodeLengthCodes> clFreq{};
    for (int i = 0; i < total;) {
        const std::uint8_t value = all[std::size_t(i)];
        int run = 1;
        while (i + run < total && all[std::size_t(i + run)] == value) ++run;
        i += run;
        if (value == 0) {
            while (run >= 11) {
                const int n = std::min(run, 138);
                codes.push_back({18, std::uint8_t(n - 11)});
                run -= n;
            }
            if (run >= 3) {
                codes.push_back({17, std::uint8_t(run - 3)});
                run = 0;
            }
        } else {
            codes.push_back({value, 0});
            --run;
            while (run >= 3) {
                const int n = std::min(run, 6);
                codes.push_back({16, std::uint8_t(n - 3)});
                run -= n;
            }
        }
        for (; run > 0; --run) codes.push_back({value, 0});
    }
    for (const Code& c : codes) ++clFreq[c.symbol];
    std::array<std::uint8_t, kCodeLengthCodes> clLengths{};
    huffmanLengths(clFreq.data(), kCodeLengthCodes, 7, clLengths.data());
    int hclen = kCodeLengthCodes;
    while (hclen > 4 && clLengths[kCodeLengthOrder[std::size_t(hclen - 1)]] == 0) --hclen;

    // Its size in bits, against storing.
    const auto extraOf = [](std::uint8_t symbol) { return symbol == 16 ? 2 : symbol == 17 ? 3 : symbol == 18 ? 7 : 0; };
    std::uint64_t bits = 3 + 5 + 5 + 4 + 3 * std::uint64_t(hclen);
    for (const Code& c : codes) bits += clLengths[c.symbol] + std::uint64_t(extraOf(c.symbol));
    for (int s = 0; s < kLitLenCodes; ++s)
        bits += std::uint64_t(block.freq[std::size_t(s)]) * litLengths[std::size_t(s)];
    bits += block.extraBits + std::uint64_t(block.matches) * std::uint64_t(1 + distance.extraBits);
    if (bits >= storedBits(inputSize, final)) {
        writeStored(out, input, inputSize, final);
        return;
    }

    std::array<std::uint16_t, kLitLenCodes> litCodes{};
    canonicalCodes(litLengths.data(), kLitLenCodes, litCodes.data());
    std::array<std::uint16_t, kDistCodes> distCodes{};
    canonicalCodes(distLengths.data(), kDistCodes, distCodes.data());
    std::array<std::uint16_t, kCodeLengthCodes> clCodes{};
    canonicalCodes(clLengths.data(), kCodeLengthCodes, clCodes.data());

    out.put(final ? 1u : 0u, 1);
    out.put(2, 2);  // dynamic Huffman codes
    out.put(std::uint32_t(hlit - 257), 5);
    out.put(std::uint32_t(hdist - 1), 5);
    out.put(std::uint32_t(hclen - 4), 4);
    for (int i = 0; i < hclen; ++i) out.put(clLengths[kCodeLengthOrder[std::size_t(i)]], 3);
    for (const Code& c : codes) {
        out.put(clCodes[c.symbol], clLengths[c.symbol]);
        if (const int extra = extraOf(c.symbol)) out.put(c.extra, extra);
    }
    const std::uint32_t distCode = distCodes[std::size_t(distance.code)] | (distance.extra << 1);
    const int distBits = 1 + distance.extraBits;
    for (const std::uint16_t token : block.tokens) {
        if (token < 256) {
            out.put(litCodes[token], litLengths[token]);
            continue;
        }
        const std::size_t length = std::size_t(token) - 256 + 3;
        const int code = kLengthCode[length];
        out.put(litCodes[std::size_t(257 + code)], litLengths[std::size_t(257 + code)]);
        if (kLengthExtra[std::size_t(code)] > 0)
            out.put(std::uint32_t(length - kLengthBase[std::size_t(code)]), kLengthExtra[std::size_t(code)]);
        out.put(distCode, distBits);
    }
    out.put(litCodes[256], litLengths[256]);
}

// How many bytes from `at` repeat the byte `step` before them (at >= step).
std::size_t runFrom(const std::uint8_t* data, std::size_t at, std::size_t size, std::size_t step) {
    std::size_t j = at;
    while (j + 8 <= size) {
        std::uint64_t a, b;
        std::memcpy(&a, data + j, 8);
        std::memcpy(&b, data + j - step, 8);
        if (a != b) {
            const std::uint64_t differ = a ^ b;
            if constexpr (std::endian::native == std::endian::little)
                return j + std::size_t(__builtin_ctzll(differ) / 8) - at;
            break;
        }
        j += 8;
    }
    while (j < size && data[j] == data[j - step]) ++j;
    return j - at;
}

}  // namespace

std::size_t runDeflateBound(std::size_t size) {
    const std::size_t blocks = size / kBlockInput + 2, pieces = size / 65535 + blocks;
    return 2 + size + 5 * pieces + blocks + 4 + 16;
}

std::size_t runDeflateZlib(std::span<const std::uint8_t> input, std::size_t step, std::uint8_t* out) {
    assert(step >= 1 && step <= 8);
    const std::uint8_t* data = input.data();
    const std::size_t size = input.size();
    out[0] = 0x78;  // deflate, 32 KiB window
    out[1] = 0x01;  // the fastest level; 0x7801 is a multiple of 31
    BitWriter bits(out + 2);

    Block block;
    block.tokens.reserve(kBlockInput + 1);
    std::size_t blockStart = 0, i = 0;
    while (i < size || blockStart == 0) {
        const std::size_t blockEnd = std::min(size, blockStart + kBlockInput);
        while (i < blockEnd) {
            const std::size_t run =
                i >= step && i + kMinRun <= size && data[i] == data[i - step] ? runFrom(data, i, size, step) : 0;
            if (run >= kMinRun) {
                i += run;
                std::size_t left = run;
                for (; left > 258; left -= 258) block.match(258);
                if (left >= 3) {
                    block.match(left);
                } else {
                    for (std::size_t k = i - left; k < i; ++k) block.literal(data[k]);
                }
                continue;
            }
            block.literal(data[i]);
            ++i;
        }
        // A run may have gone past the block's end: the block is what it covered.
        writeBlock(bits, block, data + blockStart, i - blockStart, step, i >= size);
        block.clear();
        blockStart = i;
        if (size == 0) break;
    }
    bits.align();
    std::uint8_t* end = bits.position();
    const std::uint32_t adler = libdeflate_adler32(1, data, size);
    for (int k = 0; k < 4; ++k) *end++ = std::uint8_t(adler >> (24 - 8 * k));
    return std::size_t(end - out);
}

}  // namespace frugal
