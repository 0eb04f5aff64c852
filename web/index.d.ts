// TypeScript declarations of lockbox's JavaScript API (lockbox.js). See README.md.

/** A raw Q16.16 value (lockbox.raw(n) or api.raw(n)), passed to lockbox unchanged. */
export declare class Raw {
    constructor(raw: number);
    /** The integer, in [-(2^31 - 1), 2^31 - 1]. */
    readonly raw: number;
    /** raw / 65536, exact. */
    toNumber(): number;
}

/** A raw Q32.32 value (the mouse joint's maxForce). */
export declare class RawWide {
    constructor(raw: bigint);
    readonly raw: bigint;
}

/**
 * A number as lockbox takes it: a JavaScript number (its IEEE-754 bits converted with integer
 * arithmetic, rounded to nearest with ties away from zero), a decimal string parsed exactly
 * ('0.1'), or a Raw. NaN, infinities and magnitudes beyond 32767.99998 throw a RangeError.
 */
export type Num = number | string | Raw;
/** A vector: {x, y} or [x, y]. */
export type Vec = { x: Num; y: Num } | [Num, Num];
/** A vector read back (numbers are raw / 65536, exact). */
export interface Vec2 {
    x: number;
    y: number;
}
export type BodyType = 'static' | 'kinematic' | 'dynamic';
export type JointType = 'revolute' | 'prismatic' | 'distance' | 'pulley' | 'mouse' | 'gear' | 'wheel' | 'weld' | 'friction' | 'rope';

/** b2BodyDef; fields left out keep the manual's defaults. */
export interface BodyDef {
    type?: BodyType | 0 | 1 | 2;
    position?: Vec;
    angle?: Num;
    linearVelocity?: Vec;
    angularVelocity?: Num;
    linearDamping?: Num;
    angularDamping?: Num;
    allowSleep?: boolean;
    awake?: boolean;
    fixedRotation?: boolean;
    bullet?: boolean;
    active?: boolean;
    gravityScale?: Num;
    userData?: number | bigint;
}

export type ShapeDef =
    | { type: 'circle'; radius: Num; center?: Vec }
    | { type: 'edge'; v1: Vec; v2: Vec; v0?: Vec; v3?: Vec }
    | { type: 'polygon'; vertices: Vec[]; hull?: boolean }
    | { type: 'box'; hx: Num; hy: Num; center?: Vec; angle?: Num }
    | { type: 'chain'; vertices: Vec[]; loop?: boolean; prevVertex?: Vec; nextVertex?: Vec };

export interface Filter {
    categoryBits?: number;
    maskBits?: number;
    groupIndex?: number;
}

/** b2FixtureDef with its shape. */
export interface FixtureDef {
    shape: ShapeDef;
    friction?: Num;
    restitution?: Num;
    density?: Num;
    isSensor?: boolean;
    filter?: Filter;
    userData?: number | bigint;
}

interface JointBase {
    bodyA?: Body;
    bodyB?: Body;
    collideConnected?: boolean;
    userData?: number | bigint;
}
/**
 * A joint definition. The fields of each type are the manual's; `anchor` (and `axis`,
 * `anchorA`/`anchorB` where the manual's Initialize takes them) call Initialize, which
 * computes the local anchors, axis and reference angle from world values.
 */
export type JointDef =
    | (JointBase & { type: 'revolute'; anchor?: Vec; localAnchorA?: Vec; localAnchorB?: Vec; referenceAngle?: Num; enableLimit?: boolean; lowerAngle?: Num; upperAngle?: Num; enableMotor?: boolean; motorSpeed?: Num; maxMotorTorque?: Num })
    | (JointBase & { type: 'prismatic'; anchor?: Vec; axis?: Vec; localAnchorA?: Vec; localAnchorB?: Vec; localAxisA?: Vec; referenceAngle?: Num; enableLimit?: boolean; lowerTranslation?: Num; upperTranslation?: Num; enableMotor?: boolean; maxMotorForce?: Num; motorSpeed?: Num })
    | (JointBase & { type: 'distance'; anchorA?: Vec; anchorB?: Vec; localAnchorA?: Vec; localAnchorB?: Vec; length?: Num; frequencyHz?: Num; dampingRatio?: Num })
    | (JointBase & { type: 'pulley'; groundAnchorA?: Vec; groundAnchorB?: Vec; anchorA?: Vec; anchorB?: Vec; ratio?: Num; localAnchorA?: Vec; localAnchorB?: Vec; lengthA?: Num; lengthB?: Num })
    | (JointBase & { type: 'mouse'; target?: Vec; maxForce?: Num | RawWide; frequencyHz?: Num; dampingRatio?: Num })
    | (JointBase & { type: 'gear'; joint1: Joint; joint2: Joint; ratio?: Num })
    | (JointBase & { type: 'wheel'; anchor?: Vec; axis?: Vec; localAnchorA?: Vec; localAnchorB?: Vec; localAxisA?: Vec; enableMotor?: boolean; maxMotorTorque?: Num; motorSpeed?: Num; frequencyHz?: Num; dampingRatio?: Num })
    | (JointBase & { type: 'weld'; anchor?: Vec; localAnchorA?: Vec; localAnchorB?: Vec; referenceAngle?: Num; frequencyHz?: Num; dampingRatio?: Num })
    | (JointBase & { type: 'friction'; anchor?: Vec; localAnchorA?: Vec; localAnchorB?: Vec; maxForce?: Num; maxTorque?: Num })
    | (JointBase & { type: 'rope'; localAnchorA?: Vec; localAnchorB?: Vec; maxLength?: Num });

export interface BodyState {
    position: Vec2;
    angle: number;
    linearVelocity: Vec2;
    angularVelocity: number;
    worldCenter: Vec2;
    localCenter: Vec2;
    type: BodyType;
    awake: boolean;
    active: boolean;
    bullet: boolean;
    sleepingAllowed: boolean;
    fixedRotation: boolean;
    outOfBounds: boolean;
    /** kg (Q32.32 shown as a double: display only) */
    mass: number;
    inertia: number;
    linearDamping: number;
    angularDamping: number;
    gravityScale: number;
    userData: bigint;
    /** The raw words (web/src/BodyApi.cpp, lb_body_state). */
    raw: Int32Array;
}

/** A body, named by its id (valid across snapshot restores). */
export declare class Body {
    readonly world: World;
    readonly id: number;
    getState(): BodyState;
    getPosition(): Vec2;
    getAngle(): number;
    getLinearVelocity(): Vec2;
    getAngularVelocity(): number;
    getWorldCenter(): Vec2;
    getType(): BodyType;
    isAwake(): boolean;
    getMass(): number;
    getUserData(): bigint;
    setTransform(position: Vec, angle: Num): void;
    setLinearVelocity(v: Vec): void;
    setAngularVelocity(w: Num): void;
    applyForce(force: Vec, point: Vec): void;
    applyForceToCenter(force: Vec): void;
    applyTorque(torque: Num): void;
    applyLinearImpulse(impulse: Vec, point: Vec): void;
    applyAngularImpulse(impulse: Num): void;
    setType(type: BodyType): void;
    setAwake(flag: boolean): void;
    setActive(flag: boolean): void;
    setBullet(flag: boolean): void;
    setSleepingAllowed(flag: boolean): void;
    setFixedRotation(flag: boolean): void;
    setLinearDamping(d: Num): void;
    setAngularDamping(d: Num): void;
    setGravityScale(s: Num): void;
    setUserData(data: number | bigint): void;
    getWorldPoint(p: Vec): Vec2;
    getLocalPoint(p: Vec): Vec2;
    getWorldVector(v: Vec): Vec2;
    getLocalVector(v: Vec): Vec2;
    getLinearVelocityFromWorldPoint(p: Vec): Vec2;
    createFixture(def: FixtureDef): Fixture;
    createFixture(shape: ShapeDef, density: Num): Fixture;
    destroyFixture(fixture: Fixture): void;
    /** Newest first. */
    fixtures(): Fixture[];
}

export declare class Fixture {
    readonly world: World;
    readonly id: number;
    getBody(): Body;
    getType(): 'circle' | 'edge' | 'polygon' | 'chain';
    isSensor(): boolean;
    getDensity(): number;
    getFriction(): number;
    getRestitution(): number;
    getFilterData(): Required<Filter>;
    getUserData(): bigint;
    setDensity(d: Num): void;
    setFriction(f: Num): void;
    setRestitution(r: Num): void;
    setSensor(flag: boolean): void;
    setFilterData(filter: Filter): void;
    setUserData(data: number | bigint): void;
    testPoint(p: Vec): boolean;
}

export declare class Joint {
    readonly world: World;
    readonly id: number;
    getType(): JointType;
    getBodyA(): Body;
    getBodyB(): Body;
    getAnchorA(): Vec2;
    getAnchorB(): Vec2;
    getReactionForce(invDt: Num): Vec2;
    getReactionTorque(invDt: Num): number;
    getUserData(): bigint;
    /** The type's own coordinates (angle, translation, lengths, ...). */
    getState(invDt?: Num): { type: JointType; [key: string]: unknown };
    enableMotor(flag: boolean): void;
    setMotorSpeed(speed: Num): void;
    setMaxMotorTorque(torque: Num): void;
    setMaxMotorForce(force: Num): void;
    enableLimit(flag: boolean): void;
    setLimits(lower: Num, upper: Num): void;
    setTarget(target: Vec): void;
    setFrequency(hz: Num): void;
    setDampingRatio(ratio: Num): void;
    setLength(length: Num): void;
    setMaxLength(length: Num): void;
    setRatio(ratio: Num): void;
    setMaxForce(force: Num | RawWide): void;
    setMaxTorque(torque: Num): void;
    setUserData(data: number | bigint): void;
}

export interface ContactEvent {
    /** true for BeginContact, false for EndContact */
    begin: boolean;
    fixtureA: Fixture;
    fixtureB: Fixture;
    childA: number;
    childB: number;
    bodyA: Body;
    bodyB: Body;
}

export interface RayHit {
    fixture: Fixture;
    point: Vec2;
    normal: Vec2;
    fraction: number;
}

export declare class World {
    /** A new world (gravity defaults to (0, -10)). Call destroy() when done. */
    constructor(def?: { gravity?: Vec });
    destroy(): void;
    /** One step of dt seconds: 1/60 and api.ratio(1, 60) are both raw 1092. */
    step(dt: Num, velocityIterations?: number, positionIterations?: number): void;
    clearForces(): void;
    createBody(def?: BodyDef): Body;
    destroyBody(body: Body): void;
    createJoint(def: JointDef): Joint;
    destroyJoint(joint: Joint): void;
    getBody(id: number): Body | null;
    /** In list order (newest first). */
    bodies(): Body[];
    joints(): Joint[];
    contacts(): { fixtureA: Fixture; fixtureB: Fixture; touching: boolean }[];
    getGravity(): Vec2;
    setGravity(g: Vec): void;
    getBodyCount(): number;
    getJointCount(): number;
    getContactCount(): number;
    getProxyCount(): number;
    getSaturationCount(): bigint;
    setAllowSleeping(flag: boolean): void;
    getAllowSleeping(): boolean;
    setWarmStarting(flag: boolean): void;
    getWarmStarting(): boolean;
    setContinuousPhysics(flag: boolean): void;
    getContinuousPhysics(): boolean;
    setSubStepping(flag: boolean): void;
    getSubStepping(): boolean;
    setAutoClearForces(flag: boolean): void;
    getAutoClearForces(): boolean;
    /** XXH3-64 of everything that decides future steps. */
    hash(): bigint;
    /** The hash as '0x' + 16 hex digits. */
    hashHex(): string;
    /** A snapshot: the same bytes as a native build saves. */
    save(): Uint8Array;
    /** undefined when restored; otherwise why the bytes were refused (the world is unchanged). */
    restore(bytes: Uint8Array): string | undefined;
    /** Contact begin/end events since the last call. */
    takeContactEvents(): ContactEvent[];
    queryAABB(lower: Vec, upper: Vec): Fixture[];
    rayCast(p1: Vec, p2: Vec, mode?: 'closest' | 'all' | 'any'): RayHit[];
    /** The geometry in world coordinates, raw words (README.md, "Drawing"). */
    debugDraw(): Int32Array;
}

/** A library scene (samples module only). */
export declare class Scene {
    readonly name: string;
    readonly info: { steps: number; velocityIterations: number; positionIterations: number; hz: number; allowSleep: boolean; heavy: boolean };
    readonly world: World;
    readonly stepCount: number;
    step(hz?: number, velocityIterations?: number, positionIterations?: number): void;
    destroy(): void;
}

export interface VerifyResult {
    ok: boolean;
    error?: string;
    message: string;
    report: string;
    frames: number;
    hashesChecked: number;
    firstBadFrame: number;
    expected: string;
    actual: string;
    finalHash: string;
    frameCount: number;
    tickRate: number;
    stage: number;
    solvePhase: number;
    keyframe: number;
    body: number;
    category: number;
    fieldCount: number;
    /** The differing fields of that body: values as "decimal (raw 0x...)". */
    fields: { field: string; recorded: string; resimulated: string }[];
}

/** The API over one loaded module. */
export interface Lockbox {
    World: typeof World;
    Body: typeof Body;
    Fixture: typeof Fixture;
    Joint: typeof Joint;
    Raw: typeof Raw;
    RawWide: typeof RawWide;
    /** The scene library (samples module only; null in the package's module). */
    scenes: { names(): string[]; create(name: string): Scene } | null;
    /** Replay verification (samples module only; null in the package's module). */
    replay: { verify(bytes: Uint8Array): VerifyResult } | null;
    raw(n: number): Raw;
    rawWide(n: bigint): RawWide;
    /** num/den rounded once to Q16.16 (integers). */
    ratio(num: number, den: number): Raw;
    /** Decimal text parsed exactly. */
    parse(text: string): Raw;
    /** The raw Q16.16 integer lockbox makes of a number. */
    toFixedRaw(value: Num): number;
    /** The raw Q32.32 integer lockbox makes of a number. */
    toWideRaw(value: Num | RawWide): bigint;
    fromFixedRaw(raw: number): number;
}

export interface LoadOptions {
    /** node: path of an Emscripten loader (default: the package's lockbox-wasm.js). */
    module?: string;
    /** The loader's factory function (a page: default globalThis.LockboxWasm). */
    factory?: (options: object) => Promise<object>;
    /** The .wasm bytes, instead of reading or fetching them. */
    wasmBinary?: Uint8Array;
    /** A page: where the .wasm file is. */
    locateFile?: (path: string, prefix: string) => string;
}

/** Loads the WebAssembly module and returns the API bound to it. */
export declare function load(options?: LoadOptions): Promise<Lockbox>;
