// Recorder: header, seed, then blocks of inputs and hashes, keyframes and the end record.
#include "lockbox/replay/Recorder.h"

#include <algorithm>

#include "Bytes.h"
#include "Chunks.h"
#include "StageHasher.h"
#include "lockbox/state/Snapshot.h"
#include "lockbox/state/WorldHash.h"

namespace lockbox::replay {

FileSink::FileSink(const std::string& path) : file_(std::fopen(path.c_str(), "wb")) {}

FileSink::~FileSink() { Close(); }

bool FileSink::Write(std::span<const uint8> bytes) {
    if (file_ == nullptr) return false;
    return std::fwrite(bytes.data(), 1, bytes.size(), file_) == bytes.size();
}

bool FileSink::Close() {
    if (file_ == nullptr) return true;
    const bool ok = std::fflush(file_) == 0 && std::ferror(file_) == 0;
    std::fclose(file_);
    file_ = nullptr;
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
    : world_(world), game_(game), sink_(sink), config_(std::move(config)) {
    config_.hashInterval = std::max<uint32>(config_.hashInterval, 1);
    config_.blockFrames = std::max<uint32>(config_.blockFrames, 1);
    config_.tickRate = std::max<uint16>(config_.tickRate, 1);
    config_.playerCount = std::clamp<uint16>(config_.playerCount, 1, static_cast<uint16>(kMaxPlayers));
    config_.inputBytes = std::min<uint16>(config_.inputBytes, static_cast<uint16>(kMaxInputBytes));
}

Recorder::~Recorder() = default;

void Recorder::Emit(uint32 type, std::span<const uint8> payload) {
    chunk_.clear();
    detail::EncodeChunk(type, payload, config_.compressionLevel, chunk_);
    if (!sink_.Write(chunk_) && writeError_.ok()) {
        writeError_.code = ErrorCode::e_io;
        writeError_.chunkType = type;
        writeError_.frame = frames_;
        writeError_.message = "the sink refused a write";
    }
}

Error Recorder::Begin() {
    if (begun_) return writeError_;
    begun_ = true;
    header_.engineMajor = lockbox_versionMajor;
    header_.engineMinor = lockbox_versionMinor;
    header_.enginePatch = lockbox_versionPatch;
    header_.determinismVersion = b2_determinismVersion;
    header_.snapshotFormatVersion = b2_snapshotFormatVersion;
    header_.tickRate = config_.tickRate;
    header_.timeStepRaw = Fixed::FromRatio(1, config_.tickRate).Raw();
    header_.velocityIterations = config_.velocityIterations;
    header_.positionIterations = config_.positionIterations;
    header_.worldFlags = WorldFlags(world_);
    header_.playerCount = config_.playerCount;
    header_.inputBytes = config_.inputBytes;
    header_.hashInterval = config_.hashInterval;
    header_.keyframeInterval = config_.keyframeInterval;
    scratch_.clear();
    detail::EncodeHeader(header_, scratch_);
    if (!sink_.Write(scratch_)) {
        writeError_.code = ErrorCode::e_io;
        writeError_.message = "the sink refused the header";
        return writeError_;
    }

    scratch_.clear();
    detail::ByteWriter meta(scratch_);
    const std::string& name = config_.gameName;
    meta.U16(static_cast<uint16>(std::min<size_t>(name.size(), 0xFFFF)));
    meta.Bytes(
        std::span<const uint8>(reinterpret_cast<const uint8*>(name.data()), std::min<size_t>(name.size(), 0xFFFF)));
    meta.Blob(config_.gameParams);
    Emit(e_chunkMeta, scratch_);

    std::vector<uint8> image = world_.Save();
    game_.SaveUserState(user_);
    scratch_.clear();
    detail::ByteWriter seed(scratch_);
    seed.U32(0);
    seed.U64(world_.Hash());
    seed.Blob(image);
    seed.Blob(user_);
    Emit(e_chunkSeed, scratch_);
    return writeError_;
}

std::span<const uint8> Recorder::PushInputs(std::span<const uint8> inputs) {
    const size_t frameBytes = static_cast<size_t>(config_.playerCount) * config_.inputBytes;
    const size_t at = inputBlock_.size();
    inputBlock_.resize(at + frameBytes, 0);
    std::copy_n(inputs.begin(), std::min(inputs.size(), frameBytes),
                inputBlock_.begin() + static_cast<std::ptrdiff_t>(at));
    return std::span<const uint8>(inputBlock_.data() + at, frameBytes);
}

uint64 Recorder::Advance(std::span<const uint8> inputs) {
    if (!begun_ || finished_) return 0;
    const std::span<const uint8> frameInputs = PushInputs(inputs);
    const int32 frame = frames_;
    game_.Apply(world_, frame, frameInputs);
    const Fixed dt = Fixed::FromRaw(header_.timeStepRaw);
    if (config_.stageHashes) {
        detail::StageHasher stages;
        // Stage 0 is the state Step starts from, after the inputs were applied.
        stages.BeginFrame(frame, world_);
        b2StepObserver* previous = world_.GetStepObserver();
        world_.SetStepObserver(&stages);
        world_.Step(dt, config_.velocityIterations, config_.positionIterations);
        world_.SetStepObserver(previous);
        stageBlock_.insert(stageBlock_.end(), std::begin(stages.stages), std::end(stages.stages));
        solveBlock_.insert(solveBlock_.end(), std::begin(stages.solve), std::end(stages.solve));
    } else {
        world_.Step(dt, config_.velocityIterations, config_.positionIterations);
    }
    const bool hashed = static_cast<uint32>(frame + 1) % config_.hashInterval == 0;
    const uint64 hash = hashed ? world_.Hash() : 0;
    Record(hash, &world_);
    return hash;
}

void Recorder::AppendConfirmed(std::span<const uint8> inputs, uint64 hashAfter, const b2World* worldAtFrame) {
    if (!begun_ || finished_) return;
    PushInputs(inputs);
    if (config_.stageHashes) {
        // Unknown fenceposts are stored as 0 (a frame not covered); bisect then names no stage.
        stageBlock_.insert(stageBlock_.end(), kStagesPerFrame, 0);
        solveBlock_.insert(solveBlock_.end(), kSolvePhasesPerFrame, 0);
    }
    Record(hashAfter, worldAtFrame);
}

void Recorder::Record(uint64 hash, const b2World* keyframeWorld) {
    const int32 frame = frames_;
    ++frames_;
    if (static_cast<uint32>(frames_) % config_.hashInterval == 0) {
        if (hashBlockStart_ < 0) hashBlockStart_ = frame;
        hashBlock_.push_back(hash);
    }
    const bool keyframe = config_.keyframeInterval != 0 && static_cast<uint32>(frames_) % config_.keyframeInterval == 0;
    if (keyframe || static_cast<uint32>(frames_ - blockStart_) >= config_.blockFrames) Flush();
    if (keyframe && keyframeWorld != nullptr) {
        std::vector<uint8> image = keyframeWorld->Save();
        game_.SaveUserState(user_);
        scratch_.clear();
        detail::ByteWriter w(scratch_);
        w.U32(static_cast<uint32>(frames_));
        w.U64(keyframeWorld->Hash());
        w.Blob(image);
        w.Blob(user_);
        Emit(e_chunkKeyframe, scratch_);
    }
}

void Recorder::Flush() {
    const int32 count = frames_ - blockStart_;
    if (count > 0) {
        scratch_.clear();
        detail::ByteWriter w(scratch_);
        w.U32(static_cast<uint32>(blockStart_));
        w.U32(static_cast<uint32>(count));
        w.Bytes(inputBlock_);
        Emit(e_chunkInputs, scratch_);
    }
    if (!hashBlock_.empty()) {
        scratch_.clear();
        detail::ByteWriter w(scratch_);
        w.U32(static_cast<uint32>(hashBlockStart_));
        w.U32(static_cast<uint32>(hashBlock_.size()));
        for (uint64 h : hashBlock_) w.U64(h);
        Emit(e_chunkHashes, scratch_);
    }
    EmitFrameHashes(e_chunkStages, count, kStagesPerFrame, stageBlock_);
    EmitFrameHashes(e_chunkSolve, count, kSolvePhasesPerFrame, solveBlock_);
    inputBlock_.clear();
    hashBlock_.clear();
    stageBlock_.clear();
    solveBlock_.clear();
    hashBlockStart_ = -1;
    blockStart_ = frames_;
}

void Recorder::EmitFrameHashes(uint32 type, int32 count, uint32 per, const std::vector<uint64>& block) {
    if (block.empty()) return;
    scratch_.clear();
    detail::ByteWriter w(scratch_);
    w.U32(static_cast<uint32>(blockStart_));
    w.U32(static_cast<uint32>(count));
    w.U32(per);
    for (uint64 h : block) w.U64(h);
    Emit(type, scratch_);
}

Error Recorder::Finish() {
    if (!begun_ || finished_) return writeError_;
    finished_ = true;
    Flush();
    scratch_.clear();
    detail::ByteWriter w(scratch_);
    w.U32(static_cast<uint32>(frames_));
    w.U64(world_.Hash());
    Emit(e_chunkEnd, scratch_);
    return writeError_;
}

}  // namespace lockbox::replay
