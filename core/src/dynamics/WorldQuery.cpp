// b2World queries (AABB, ray cast) and debug drawing.
#include "dynamics/WorldState.h"
#include "lockbox/collision/ChainShape.h"
#include "lockbox/collision/CircleShape.h"
#include "lockbox/collision/EdgeShape.h"
#include "lockbox/collision/PolygonShape.h"
#include "lockbox/dynamics/Draw.h"
#include "lockbox/dynamics/World.h"
#include "lockbox/dynamics/contacts/Contact.h"

namespace lockbox {

using World = core_detail::Engine::World;

namespace {

// Broad-phase user data are fixture ids (b2FixtureProxy::MakeKey), resolved through the pool.
struct WorldQueryWrapper {
    bool QueryCallback(int32 proxyId) {
        const uint64 key = broadPhase->GetUserData(proxyId);
        b2Fixture* fixture = fixtures->Get(b2FixtureProxy::KeyFixture(key));
        return callback->ReportFixture(fixture);
    }
    const b2BroadPhase* broadPhase;
    b2Pool<b2Fixture>* fixtures;
    b2QueryCallback* callback;
};

struct WorldRayCastWrapper {
    Fixed RayCastCallback(const b2RayCastInput& input, int32 proxyId) {
        const uint64 key = broadPhase->GetUserData(proxyId);
        b2Fixture* fixture = fixtures->Get(b2FixtureProxy::KeyFixture(key));
        const int32 index = b2FixtureProxy::KeyChild(key);
        b2RayCastOutput output;
        if (fixture->RayCast(&output, input, index)) {
            const Fixed fraction = output.fraction;
            // p1 + fraction * (p2 - p1): one rounding per axis (equal to (1-f) p1 + f p2 up to it).
            const b2Vec2 point = input.p1 + fraction * (input.p2 - input.p1);
            return callback->ReportFixture(fixture, point, output.normal, fraction);
        }
        return input.maxFraction;
    }
    const b2BroadPhase* broadPhase;
    b2Pool<b2Fixture>* fixtures;
    b2RayCastCallback* callback;
};

}  // namespace

void World::QueryAABB(b2QueryCallback* callback, const b2AABB& aabb) const {
    WorldQueryWrapper wrapper{&m_contactManager.m_broadPhase, const_cast<b2Pool<b2Fixture>*>(&m_fixtures), callback};
    m_contactManager.m_broadPhase.Query(&wrapper, aabb);
}

void World::RayCast(b2RayCastCallback* callback, const b2Vec2& point1, const b2Vec2& point2) const {
    WorldRayCastWrapper wrapper{&m_contactManager.m_broadPhase, const_cast<b2Pool<b2Fixture>*>(&m_fixtures), callback};
    b2RayCastInput input;
    input.maxFraction = 1;
    input.p1 = point1;
    input.p2 = point2;
    m_contactManager.m_broadPhase.RayCast(&wrapper, input);
}

void World::DrawShape(b2Fixture* fixture, const b2Transform& xf, const b2Color& color) {
    switch (fixture->GetType()) {
        case b2Shape::e_circle: {
            const auto* circle = static_cast<const b2CircleShape*>(fixture->m_shape.get());
            const b2Vec2 center = b2Mul(xf, circle->m_p);
            const b2Vec2 axis = b2Mul(xf.q, b2Vec2(1, 0));
            m_debugDraw->DrawSolidCircle(center, circle->m_radius, axis, color);
            break;
        }
        case b2Shape::e_edge: {
            const auto* edge = static_cast<const b2EdgeShape*>(fixture->m_shape.get());
            m_debugDraw->DrawSegment(b2Mul(xf, edge->m_vertex1), b2Mul(xf, edge->m_vertex2), color);
            break;
        }
        case b2Shape::e_chain: {
            const auto* chain = static_cast<const b2ChainShape*>(fixture->m_shape.get());
            if (chain->m_count < 2) break;
            b2Vec2 v1 = b2Mul(xf, chain->m_vertices[0]);
            for (int32 i = 1; i < chain->m_count; ++i) {
                const b2Vec2 v2 = b2Mul(xf, chain->m_vertices[static_cast<size_t>(i)]);
                m_debugDraw->DrawSegment(v1, v2, color);
                m_debugDraw->DrawCircle(v1, Fixed(0.05), color);
                v1 = v2;
            }
            break;
        }
        case b2Shape::e_polygon: {
            const auto* poly = static_cast<const b2PolygonShape*>(fixture->m_shape.get());
            b2Vec2 vertices[b2_maxPolygonVertices];
            for (int32 i = 0; i < poly->m_vertexCount; ++i) vertices[i] = b2Mul(xf, poly->m_vertices[i]);
            m_debugDraw->DrawSolidPolygon(vertices, poly->m_vertexCount, color);
            break;
        }
        default: break;
    }
}

void World::DrawDebugData() {
    if (m_debugDraw == nullptr) return;
    const uint32 flags = m_debugDraw->GetFlags();

    if (flags & b2Draw::e_shapeBit) {
        for (b2Body* b = m_bodyList; b; b = b->GetNext()) {
            const b2Transform& xf = b->GetTransform();
            for (b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext()) {
                if (!b->IsActive()) {
                    DrawShape(f, xf, b2Color(0.5f, 0.5f, 0.3f));
                } else if (b->GetType() == b2_staticBody) {
                    DrawShape(f, xf, b2Color(0.5f, 0.9f, 0.5f));
                } else if (b->GetType() == b2_kinematicBody) {
                    DrawShape(f, xf, b2Color(0.5f, 0.5f, 0.9f));
                } else if (!b->IsAwake()) {
                    DrawShape(f, xf, b2Color(0.6f, 0.6f, 0.6f));
                } else {
                    DrawShape(f, xf, b2Color(0.9f, 0.7f, 0.7f));
                }
            }
        }
    }

    if (flags & b2Draw::e_jointBit) {
        // Joint drawing arrives with the concrete joints; draw the anchor links meanwhile.
        for (b2Joint* j = m_jointList; j; j = j->GetNext()) {
            m_debugDraw->DrawSegment(j->GetAnchorA(), j->GetAnchorB(), b2Color(0.5f, 0.8f, 0.8f));
        }
    }

    if (flags & b2Draw::e_pairBit) {
        const b2Color color(0.3f, 0.9f, 0.9f);
        for (b2Contact* c = m_contactManager.m_contactList; c; c = c->GetNext()) {
            const b2Vec2 cA = c->GetFixtureA()->GetAABB(c->GetChildIndexA()).GetCenter();
            const b2Vec2 cB = c->GetFixtureB()->GetAABB(c->GetChildIndexB()).GetCenter();
            m_debugDraw->DrawSegment(cA, cB, color);
        }
    }

    if (flags & b2Draw::e_aabbBit) {
        const b2Color color(0.9f, 0.3f, 0.9f);
        const b2BroadPhase* bp = &m_contactManager.m_broadPhase;
        for (b2Body* b = m_bodyList; b; b = b->GetNext()) {
            if (!b->IsActive()) continue;
            for (b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext()) {
                for (int32 i = 0; i < f->m_proxyCount; ++i) {
                    const b2AABB aabb = bp->GetFatAABB(f->m_proxies[static_cast<size_t>(i)].proxyId);
                    b2Vec2 vs[4];
                    vs[0].Set(aabb.lowerBound.x, aabb.lowerBound.y);
                    vs[1].Set(aabb.upperBound.x, aabb.lowerBound.y);
                    vs[2].Set(aabb.upperBound.x, aabb.upperBound.y);
                    vs[3].Set(aabb.lowerBound.x, aabb.upperBound.y);
                    m_debugDraw->DrawPolygon(vs, 4, color);
                }
            }
        }
    }

    if (flags & b2Draw::e_centerOfMassBit) {
        for (b2Body* b = m_bodyList; b; b = b->GetNext()) {
            b2Transform xf = b->GetTransform();
            xf.p = b->GetWorldCenter();
            m_debugDraw->DrawTransform(xf);
        }
    }
}

}  // namespace lockbox
