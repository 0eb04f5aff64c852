// b2CircleShape: validation, point test, exact ray cast, AABB and mass.

#include "lockbox/collision/CircleShape.h"

#include "ShapeInternal.h"

namespace lockbox {

using shape_detail::S128;

namespace {
// pi * 2^32 correctly rounded (13493037704.522...): relative error 3.5e-11, far below the
// Q32.32 rounding of any mass in the envelope.
constexpr int64_t kPiQ32 = 13493037705;

// Scales a raw int64 vector component down by 2^shift with rounding (ties away from zero).
constexpr int64_t ShiftDown(int64_t v, int shift) noexcept {
    if (shift == 0) return v;
    return detail::ShiftRound(v, shift);
}
}  // namespace

b2CircleShape::b2CircleShape(Fixed radius, const b2Vec2& center, b2ShapeError* error) noexcept
    : b2Shape(e_circle, Fixed()) {
    const b2ShapeError result = Set(center, radius);
    if (error != nullptr) *error = result;
}

b2ShapeError b2CircleShape::Set(const b2Vec2& center, Fixed radius) noexcept {
    if (radius.Raw() <= 0) return b2ShapeError::nonPositiveRadius;
    const int64_t limit = b2_maxShapeCoordinate.Raw();
    const int64_t r = radius.Raw();
    if (detail::AbsU64(center.x.Raw()) + r > static_cast<uint64_t>(limit) ||
        detail::AbsU64(center.y.Raw()) + r > static_cast<uint64_t>(limit)) {
        return b2ShapeError::outOfRange;
    }
    m_p = center;
    m_radius = radius;
    return b2ShapeError::ok;
}

std::unique_ptr<b2Shape> b2CircleShape::Clone() const { return std::make_unique<b2CircleShape>(*this); }

bool b2CircleShape::TestPoint(const b2Transform& transform, const b2Vec2& p) const {
    const b2Vec2 center = transform.p + b2Mul(transform.q, m_p);
    // Differences may reach 2^32 raw across the whole Q16.16 range, so square in 128 bits.
    const int64_t dx = int64_t{p.x.Raw()} - center.x.Raw();
    const int64_t dy = int64_t{p.y.Raw()} - center.y.Raw();
    const S128 d2 = detail::AddS128(detail::MulS64(dx, dx), detail::MulS64(dy, dy));
    return shape_detail::Compare(d2, detail::MulS64(m_radius.Raw(), m_radius.Raw())) <= 0;
}

bool b2CircleShape::RayCast(b2RayCastOutput* output, const b2RayCastInput& input, const b2Transform& transform,
                            int32 childIndex) const {
    (void)childIndex;
    const b2Vec2 position = transform.p + b2Mul(transform.q, m_p);
    int64_t sx = int64_t{input.p1.x.Raw()} - position.x.Raw();
    int64_t sy = int64_t{input.p1.y.Raw()} - position.y.Raw();
    int64_t rx = int64_t{input.p2.x.Raw()} - input.p1.x.Raw();
    int64_t ry = int64_t{input.p2.y.Raw()} - input.p1.y.Raw();
    int64_t radius = m_radius.Raw();
    // The discriminant is quartic in length (NUMERICS Table 2). Keep every operand below 2^30
    // raw so dot products stay below 2^61 and the discriminant below 2^123: only rays or
    // offsets longer than 16384 m are scaled down, losing bits in proportion.
    uint64_t largest = detail::AbsU64(radius);
    for (int64_t v : {sx, sy, rx, ry}) largest = detail::AbsU64(v) > largest ? detail::AbsU64(v) : largest;
    int shift = 0;
    while ((largest >> shift) >= (uint64_t{1} << 30)) ++shift;
    sx = ShiftDown(sx, shift);
    sy = ShiftDown(sy, shift);
    rx = ShiftDown(rx, shift);
    ry = ShiftDown(ry, shift);
    radius = ShiftDown(radius, shift);

    const int64_t b = sx * sx + sy * sy - radius * radius;  // |s|^2 - r^2
    if (b < 0) return false;  // starts strictly inside: no hit (2.2.1 gets this from a < 0)
    const int64_t c = sx * rx + sy * ry;
    const int64_t rr = rx * rx + ry * ry;
    if (rr == 0) return false;  // zero-length ray (2.2.1: rr < epsilon; exact zero here)
    const S128 sigma = detail::SubS128(detail::MulS64(c, c), detail::MulS64(rr, b));
    if (sigma.negative) return false;
    // Rounded root of the exact discriminant: floor, then up when sigma - root^2 > root.
    uint64_t root = shape_detail::IsqrtFloor128(sigma.mag);
    const detail::U128 rem = detail::SubU128(sigma.mag, detail::MulU64(root, root));
    if (rem.hi != 0 || rem.lo > root) ++root;
    // a = -(c + sqrt(sigma)); |a| < 2^62.
    const int64_t a = -(c + static_cast<int64_t>(root));
    if (a < 0) return false;
    if (shape_detail::CompareProducts(a, Fixed::kOneRaw, input.maxFraction.Raw(), rr) > 0) return false;

    output->fraction = Fixed::FromRatio(a, rr);
    // Normal along s + (a / rr) r, formed with 16 extra bits so that small circles keep their
    // direction, then scaled below 2^30 for Normalize.
    int64_t n[2];
    const int64_t s[2] = {sx, sy}, r[2] = {rx, ry};
    for (int i = 0; i < 2; ++i) {
        const S128 num = detail::MulS128S64(detail::MulS64(a, r[i]), int64_t{1} << 16);
        const S128 q = detail::DivRoundS128(num, shape_detail::ToS128(rr));
        n[i] = s[i] * (int64_t{1} << 16) + detail::ToS64(q);
    }
    uint64_t big = detail::AbsU64(n[0]) > detail::AbsU64(n[1]) ? detail::AbsU64(n[0]) : detail::AbsU64(n[1]);
    int down = 0;
    while ((big >> down) >= (uint64_t{1} << 30)) ++down;
    b2Vec2 normal(Fixed::FromRaw(static_cast<int32_t>(ShiftDown(n[0], down))),
                  Fixed::FromRaw(static_cast<int32_t>(ShiftDown(n[1], down))));
    normal.Normalize();
    output->normal = normal;
    return true;
}

void b2CircleShape::ComputeAABB(b2AABB* aabb, const b2Transform& transform, int32 childIndex) const {
    (void)childIndex;
    // Most circles sit on their body's origin: rotating a zero offset gives zero exactly.
    const bool centred = m_p.x == Fixed() && m_p.y == Fixed();
    const b2Vec2 p = centred ? transform.p : transform.p + b2Mul(transform.q, m_p);
    aabb->lowerBound.Set(p.x - m_radius, p.y - m_radius);
    aabb->upperBound.Set(p.x + m_radius, p.y + m_radius);
}

void b2CircleShape::ComputeMass(b2MassData* massData, Fixed density) const {
    // r^2 as a Q32.32 raw (< 2^62), then density * pi * r^2 with one rounding:
    // Q32.32 * Q16.16 * Q?.32 has 80 fraction bits, < 2^127 in magnitude.
    const int64_t r2 = int64_t{m_radius.Raw()} * m_radius.Raw();
    const S128 rho_r2 = detail::MulS64(r2, density.Raw());
    const int64_t mass = shape_detail::MulShiftNarrow(rho_r2, kPiQ32, 48, "b2CircleShape::ComputeMass mass");
    massData->mass = Wide::FromRaw(mass);
    massData->center = m_p;
    // I = m (r^2 / 2 + |p|^2) = m (r^2 + 2 |p|^2) / 2, formed exactly but for the mass rounding.
    const S128 pp = detail::AddS128(detail::MulS64(m_p.x.Raw(), m_p.x.Raw()), detail::MulS64(m_p.y.Raw(), m_p.y.Raw()));
    const S128 t = detail::AddS128(shape_detail::ToS128(r2), detail::AddS128(pp, pp));
    massData->I = Wide::FromRaw(shape_detail::MulShiftNarrow(t, mass, 33, "b2CircleShape::ComputeMass I"));
}

}  // namespace lockbox
