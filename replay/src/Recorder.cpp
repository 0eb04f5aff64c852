// Recorder: header, seed, then blocks of inputs and hashes, keyframes and the end record.
#include "lockbox/replay/Recorder.h"

#include <algorithm>

#include "Chunks.h"
#include "StageHasher.h"
#include "lockbox/common/Bytes.h"
#include "lockbox/state/Snapshot.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::replay {

FileSink::FileSink(const std::string& path) : m_file(std::fopen(path.c_str(), "wb")) {}

FileSink::~FileSink() { Close(); }

bool FileSink::Write(std::span<const uint8> bytes) {
    if (m_file == nullptr) return false;
    return std::fwrite(bytes.data(), 1, bytes.size(), m_file) == bytes.size();
}

bool FileSink::Close() {
    if (m_file == nullptr) return true;
    const bool ok = std::fflush(m_file) == 0 && std::ferror(m_file) == 0;
    std::fclose(m_file);
    m_file = nullptr;
    return ok;
}

namespace {

uint32 WorldFlags(const b2World& w) {
    uint32 f = 0;
    if (w.GetAllowSleeping()) f |= e_flagAllowSleep;
    if (w.GetWarmStarting()) f |= e_flagWarmStarting;
    if (w.GetContinuousPhysics()) f |= e_flagContinuous;
    if (w.GetSubStepping()) f |= e_flagSubStepping;
    if (w.GetAutoClearForces()) f |= e_flagAutoClearForces;
    return f;
}

}  // namespace

Recorder::Recorder(b2World& world, Game& game, Sink& sink, RecorderConfig config)
    : m_world(world), m_game(game), m_sink(sink), m_config(std::move(config)) {
    m_config.hashInterval = std::max<uint32>(m_config.hashInterval, 1);
    m_config.blockFrames = std::max<uint32>(m_config.blockFrames, 1);
    m_config.tickRate = std::max<uint16>(m_config.tickRate, 1);
    m_config.playerCount = std::clamp<uint16>(m_config.playerCount, 1, static_cast<uint16>(kMaxPlayers));
    m_config.inputBytes = std::min<uint16>(m_config.inputBytes, static_cast<uint16>(kMaxInputBytes));
}

Recorder::~Recorder() = default;

void Recorder::Emit(uint32 type, std::span<const uint8> payload) {
    m_chunk.clear();
    detail::EncodeChunk(type, payload, m_config.compressionLevel, m_chunk);
    if (!m_sink.Write(m_chunk) && m_writeError.ok()) {
        m_writeError.code = ErrorCode::e_io;
        m_writeError.chunkType = type;
        m_writeError.frame = m_frames;
        m_writeError.message = "the sink refused a write";
    }
}

Error Recorder::Begin() {
    if (m_begun) return m_writeError;
    m_begun = true;
    m_header.engineMajor = b2_snapshotEngineMajor;
    m_header.engineMinor = b2_snapshotEngineMinor;
    m_header.enginePatch = b2_snapshotEnginePatch;
    m_header.determinismVersion = b2_determinismVersion;
    m_header.snapshotFormatVersion = b2_snapshotFormatVersion;
    m_header.tickRate = m_config.tickRate;
    m_header.timeStepRaw = Fixed::FromRatio(1, m_config.tickRate).Raw();
    m_header.velocityIterations = m_config.velocityIterations;
    m_header.positionIterations = m_config.positionIterations;
    m_header.worldFlags = WorldFlags(m_world);
    m_header.playerCount = m_config.playerCount;
    m_header.inputBytes = m_config.inputBytes;
    m_header.hashInterval = m_config.hashInterval;
    m_header.keyframeInterval = m_config.keyframeInterval;
    m_scratch.clear();
    detail::EncodeHeader(m_header, m_scratch);
    if (!m_sink.Write(m_scratch)) {
        m_writeError.code = ErrorCode::e_io;
        m_writeError.message = "the sink refused the header";
        return m_writeError;
    }

    m_scratch.clear();
    bytes::Writer meta(m_scratch);
    const std::string& name = m_config.gameName;
    meta.U16(static_cast<uint16>(std::min<size_t>(name.size(), 0xFFFF)));
    meta.Bytes(
        std::span<const uint8>(reinterpret_cast<const uint8*>(name.data()), std::min<size_t>(name.size(), 0xFFFF)));
    meta.Blob(m_config.gameParams);
    Emit(e_chunkMeta, m_scratch);

    std::vector<uint8> image = m_world.Save();
    m_game.SaveUserState(m_user);
    m_scratch.clear();
    bytes::Writer seed(m_scratch);
    seed.U32(0);
    seed.U64(m_world.Hash());
    seed.Blob(image);
    seed.Blob(m_user);
    Emit(e_chunkSeed, m_scratch);
    return m_writeError;
}

std::span<const uint8> Recorder::PushInputs(std::span<const uint8> inputs) {
    const size_t frameBytes = static_cast<size_t>(m_config.playerCount) * m_config.inputBytes;
    const size_t at = m_inputBlock.size();
    m_inputBlock.resize(at + frameBytes, 0);
    std::copy_n(inputs.begin(), std::min(inputs.size(), frameBytes),
                m_inputBlock.begin() + static_cast<std::ptrdiff_t>(at));
    return std::span<const uint8>(m_inputBlock.data() + at, frameBytes);
}

uint64 Recorder::Advance(std::span<const uint8> inputs) {
    if (!m_begun || m_finished) return 0;
    const std::span<const uint8> frameInputs = PushInputs(inputs);
    const int32 frame = m_frames;
    m_game.Apply(m_world, frame, frameInputs);
    const Fixed dt = Fixed::FromRaw(m_header.timeStepRaw);
    if (m_config.stageHashes) {
        detail::StageHasher stages;
        // Stage 0 is the state Step starts from, after the inputs were applied.
        stages.BeginFrame(frame, m_world);
        b2StepObserver* previous = m_world.GetStepObserver();
        m_world.SetStepObserver(&stages);
        m_world.Step(dt, m_config.velocityIterations, m_config.positionIterations);
        m_world.SetStepObserver(previous);
        m_stageBlock.insert(m_stageBlock.end(), std::begin(stages.stages), std::end(stages.stages));
        m_solveBlock.insert(m_solveBlock.end(), std::begin(stages.solve), std::end(stages.solve));
    } else {
        m_world.Step(dt, m_config.velocityIterations, m_config.positionIterations);
    }
    const bool hashed = static_cast<uint32>(frame + 1) % m_config.hashInterval == 0;
    const uint64 hash = hashed ? m_world.Hash() : 0;
    Record(hash, &m_world, nullptr);
    return hash;
}

void Recorder::AppendConfirmed(std::span<const uint8> inputs, uint64 hashAfter, const b2World* worldAtFrame) {
    if (!m_begun || m_finished) return;
    PushInputs(inputs);
    if (m_config.stageHashes) {
        // Unknown fenceposts are stored as 0 (a frame not covered); bisect then names no stage.
        m_stageBlock.insert(m_stageBlock.end(), kStagesPerFrame, 0);
        m_solveBlock.insert(m_solveBlock.end(), kSolvePhasesPerFrame, 0);
    }
    Record(hashAfter, worldAtFrame, nullptr);
}

bool Recorder::KeyframeDue() const noexcept {
    return m_config.keyframeInterval != 0 && static_cast<uint32>(m_frames + 1) % m_config.keyframeInterval == 0;
}

void Recorder::AppendFinal(std::span<const uint8> inputs, uint64 hashAfter, const Keyframe* stateAfter) {
    if (!m_begun || m_finished) return;
    PushInputs(inputs);
    if (m_config.stageHashes) {
        m_stageBlock.insert(m_stageBlock.end(), kStagesPerFrame, 0);
        m_solveBlock.insert(m_solveBlock.end(), kSolvePhasesPerFrame, 0);
    }
    Record(hashAfter, nullptr, stateAfter);
}

void Recorder::Record(uint64 hash, const b2World* keyframeWorld, const Keyframe* keyframeState) {
    const int32 frame = m_frames;
    ++m_frames;
    if (static_cast<uint32>(m_frames) % m_config.hashInterval == 0) {
        if (m_hashBlockStart < 0) m_hashBlockStart = frame;
        m_hashBlock.push_back(hash);
    }
    const bool keyframe =
        m_config.keyframeInterval != 0 && static_cast<uint32>(m_frames) % m_config.keyframeInterval == 0;
    if (keyframe || static_cast<uint32>(m_frames - m_blockStart) >= m_config.blockFrames) Flush();
    if (!keyframe) return;
    if (keyframeWorld != nullptr) {
        std::vector<uint8> image = keyframeWorld->Save();
        m_game.SaveUserState(m_user);
        EmitKeyframe(keyframeWorld->Hash(), image, m_user);
    } else if (keyframeState != nullptr) {
        EmitKeyframe(keyframeState->hash, keyframeState->world, keyframeState->user);
    }
}

void Recorder::EmitKeyframe(uint64 hash, std::span<const uint8> image, std::span<const uint8> user) {
    m_scratch.clear();
    bytes::Writer w(m_scratch);
    w.U32(static_cast<uint32>(m_frames));
    w.U64(hash);
    w.Blob(image);
    w.Blob(user);
    Emit(e_chunkKeyframe, m_scratch);
}

void Recorder::Flush() {
    const int32 count = m_frames - m_blockStart;
    if (count > 0) {
        m_scratch.clear();
        bytes::Writer w(m_scratch);
        w.U32(static_cast<uint32>(m_blockStart));
        w.U32(static_cast<uint32>(count));
        w.Bytes(m_inputBlock);
        Emit(e_chunkInputs, m_scratch);
    }
    if (!m_hashBlock.empty()) {
        m_scratch.clear();
        bytes::Writer w(m_scratch);
        w.U32(static_cast<uint32>(m_hashBlockStart));
        w.U32(static_cast<uint32>(m_hashBlock.size()));
        for (uint64 h : m_hashBlock) w.U64(h);
        Emit(e_chunkHashes, m_scratch);
    }
    EmitFrameHashes(e_chunkStages, count, kStagesPerFrame, m_stageBlock);
    EmitFrameHashes(e_chunkSolve, count, kSolvePhasesPerFrame, m_solveBlock);
    m_inputBlock.clear();
    m_hashBlock.clear();
    m_stageBlock.clear();
    m_solveBlock.clear();
    m_hashBlockStart = -1;
    m_blockStart = m_frames;
}

void Recorder::EmitFrameHashes(uint32 type, int32 count, uint32 per, const std::vector<uint64>& block) {
    if (block.empty()) return;
    m_scratch.clear();
    bytes::Writer w(m_scratch);
    w.U32(static_cast<uint32>(m_blockStart));
    w.U32(static_cast<uint32>(count));
    w.U32(per);
    for (uint64 h : block) w.U64(h);
    Emit(type, m_scratch);
}

Error Recorder::Finish() {
    if (!m_begun || m_finished) return m_writeError;
    return Finish(m_world.Hash());
}

Error Recorder::Finish(uint64 finalHash) {
    if (!m_begun || m_finished) return m_writeError;
    m_finished = true;
    Flush();
    m_scratch.clear();
    bytes::Writer w(m_scratch);
    w.U32(static_cast<uint32>(m_frames));
    w.U64(finalHash);
    Emit(e_chunkEnd, m_scratch);
    return m_writeError;
}

}  // namespace lockbox::replay
