// ClothSharp: the hand-written layer over the generated binding (Native,
// written by generate.py from cloth.h). Owners that destroy what they
// created (World, Fabric, Cloth, Body, Collider), array and Span overloads
// for particle data, and results turned into exceptions. Everything it does
// not wrap is one call away in Native, with each owner's Id. The owners are
// partial: their get/set properties of one shape (a cloth_get_X /
// cloth_set_X pair of a struct, float, double or enum: Cloth.Solver,
// Cloth.Importance, ...) are generated into ClothSharp.g.cs
// (generate.py --properties); the pairs of other shapes are here.
//
// The error model (README, "Errors"): a method either does what it says or
// throws, and a method that threw changed nothing. ClothException carries
// the cloth_result and the library's message for the call
// (cloth_get_last_error, read on the same thread right after it);
// ArgumentException and its kin report a buffer of the wrong shape before
// any native call; ObjectDisposedException a disposed owner or an object of
// a disposed world; DllNotFoundException (Native.LibraryNotFound) a missing
// native library, naming the file and where it was looked for.
// World.Step throws only when the world did not advance; when it advanced
// it returns how (ClothStepOutcome: Ok, or a degraded step). The log
// handler gets the messages of what did not throw (warnings, the step
// outcomes); an error that becomes an exception is not logged as well.
//
// Particle indices, counts and rates are int; flags are bool; points,
// directions, rotations and matrices also take System.Numerics' Vector3,
// Quaternion and Matrix4x4 (and under Unity, UnityEngine's): Float3 and
// Float4 convert to and from them implicitly, and the array and span
// overloads read and write them in place (the same layout).
//
// Compiles as C# 7.2 (Mono 6.8's mcs, Unity 2021.2+, Godot 4 / .NET 6+)
// with unsafe code allowed; references System.Numerics. Span<T> overloads
// are left out when CLOTH_NO_SPAN is defined (runtimes without System.Span).
using System;
using System.Collections.Concurrent;
using System.Numerics;
using System.Runtime.InteropServices;
#if UNITY_5_3_OR_NEWER
using MonoPInvokeCallbackAttribute = AOT.MonoPInvokeCallbackAttribute;
#endif

namespace ClothSharp
{
#if !UNITY_5_3_OR_NEWER
    /// <summary>
    /// Marks a static method that native code calls through a function pointer. Ahead-of-time
    /// runtimes (Mono full AOT, and Unity's IL2CPP, which ships its own AOT.MonoPInvokeCallbackAttribute
    /// used instead under Unity) emit a native entry for such a method; they find the attribute by
    /// its name. Callbacks given to the library are static and reach their state through the
    /// `user` pointer, as those runtimes require.
    /// </summary>
    [AttributeUsage(AttributeTargets.Method)]
    public sealed class MonoPInvokeCallbackAttribute : Attribute
    {
        public MonoPInvokeCallbackAttribute(Type type) { DelegateType = type; }
        public Type DelegateType { get; private set; }
    }
#endif

    /// <summary>A call of the C API failed: Result is its cloth_result, Message names it and explains it.</summary>
    public sealed class ClothException : Exception
    {
        public ClothResult Result { get; private set; }
        /// <summary>The library's message (cloth_get_last_error) without the result name.</summary>
        public string LibraryMessage { get; private set; }

        public ClothException(ClothResult result, string libraryMessage)
            : base(Native.cloth_result_name_str(result) + ": " + libraryMessage)
        {
            Result = result;
            LibraryMessage = libraryMessage;
        }

        /// <summary>Throws unless result is Ok. Call it on the thread that made the call, right after it.</summary>
        public static void Check(ClothResult result)
        {
            if (result != ClothResult.Ok) throw new ClothException(result, Native.cloth_get_last_error_str());
        }
    }

    /// <summary>
    /// How World.Step advanced the world: Ok, or a step that advanced but not fully as asked (the
    /// log handler gets the library's message for it; ClothLibrary.LastError holds it too).
    /// </summary>
    public enum ClothStepOutcome
    {
        /// <summary>Every cloth stepped as asked.</summary>
        Ok = ClothResult.Ok,
        /// <summary>The frame budget ran out: some cloths stepped at a lower quality or later.</summary>
        OverBudget = ClothResult.ErrorOverBudget,
        /// <summary>A solver stopped at its iteration limit: the cloths moved, less accurately.</summary>
        SolverFailed = ClothResult.ErrorSolverFailed,
        /// <summary>A cloth went non-finite and was restored to where it was; the others moved.</summary>
        NonfiniteState = ClothResult.ErrorNonfiniteState,
        /// <summary>The CG reference solver ran out of memory for a cloth, which stayed; the others moved.</summary>
        OutOfMemory = ClothResult.ErrorOutOfMemory,
    }

    /// <summary>Library-wide checks and names.</summary>
    public static class ClothLibrary
    {
        /// <summary>The loaded library's version (not the header's).</summary>
        public static ClothVersion Version { get { return Load(); } }

        /// <summary>
        /// The loaded library's version; the native library is loaded by this first call. Throws
        /// Native.LibraryNotFound's DllNotFoundException (which file, where it was looked for) when it
        /// is missing, and EntryPointNotFoundException-wrapping InvalidOperationException when it is too old.
        /// </summary>
        public static ClothVersion Load()
        {
            try { return Native.cloth_get_version(); }
            catch (DllNotFoundException e) { throw Native.LibraryNotFound(e); }
        }

        /// <summary>
        /// Throws unless the loaded library can serve this binding: the same major version, at least
        /// the header's minor version, and every struct of the binding the library's size.
        /// </summary>
        public static void Verify()
        {
            ClothVersion v = Load();
            if (v.Major != Native.CLOTH_VERSION_MAJOR || v.Minor < Native.CLOTH_VERSION_MINOR)
            {
                throw new InvalidOperationException("cloth library " + v.Major + "." + v.Minor + "." + v.Patch +
                                                    " cannot serve a binding of cloth.h " + Native.CLOTH_VERSION_MAJOR +
                                                    "." + Native.CLOTH_VERSION_MINOR);
            }
            string[] mismatches = Native.CheckStructLayouts();
            if (mismatches.Length != 0)
            {
                throw new InvalidOperationException("struct layouts differ from the library: " +
                                                    string.Join("; ", mismatches));
            }
        }

        /// <summary>cloth_result_name, copied.</summary>
        public static string ResultName(ClothResult result) { return Native.cloth_result_name_str(result); }

        /// <summary>cloth_stage_name, copied once per stage and cached (the names are static).</summary>
        public static string StageName(ClothStage stage) { return StaticNames.Get(Native.cloth_stage_name(stage)); }

        /// <summary>The message of the last failed call on this thread (cloth_get_last_error), copied.</summary>
        public static string LastError { get { return Native.cloth_get_last_error_str(); } }
    }

    /// <summary>Copies of the library's static strings, keyed by their address (cloth.h promises the same
    /// pointer for the same name), so a zone callback allocates nothing after a name's first use.</summary>
    internal static class StaticNames
    {
        static readonly ConcurrentDictionary<IntPtr, string> names = new ConcurrentDictionary<IntPtr, string>();

        public static string Get(IntPtr name)
        {
            string s;
            if (names.TryGetValue(name, out s)) return s;
            s = Utf8.ToString(name);
            names.TryAdd(name, s);
            return s;
        }
    }

    /// <summary>
    /// Memory for a world (cloth_world_desc.alloc/free). Called on the thread that makes the API call
    /// (and on the finalizer thread for a world that was never disposed): make it thread-safe if
    /// several worlds share it. Allocate returns IntPtr.Zero on failure (the call then fails with
    /// ErrorOutOfMemory and changes nothing); alignment is a power of two up to 64, and Free receives
    /// the pointer Allocate returned, with its size. Exceptions thrown here are caught and count as a
    /// failed allocation (they must not cross into native code).
    /// </summary>
    public abstract class ClothAllocator
    {
        public abstract IntPtr Allocate(ulong size, ulong alignment);
        public abstract void Free(IntPtr pointer, ulong size);
    }

    /// <summary>
    /// Receives the world's messages (cloth_world_desc.log) on the calling thread: warnings, info
    /// and the messages of the step outcomes World.Step returns. An error that ClothSharp throws as
    /// a ClothException is not passed here as well (the exception carries its message).
    /// </summary>
    public delegate void ClothLogHandler(ClothLogLevel level, ClothResult code, string message);

    /// <summary>
    /// Profiler zones (cloth_world_set_zone_callbacks). Called on the thread that runs the work, the
    /// world's workers included, concurrently: keep it cheap and thread-safe, and call no cloth API.
    /// </summary>
    public interface IClothZoneListener
    {
        void Begin(string name, int worker);
        void End(string name, int worker);
    }

    /// <summary>
    /// A world (cloth_world_id) and everything in it. Dispose destroys it and every object in it; a
    /// world never disposed is destroyed by its finalizer. Threading (cloth.h): one thread at a time
    /// calls a world and the objects in it, and none while Step runs.
    /// </summary>
    public sealed partial class World : IDisposable
    {
        // What the static callbacks reach through `user`: kept by a GCHandle for the native world's
        // lifetime. It does not reference the World, so an abandoned World can still be finalized.
        sealed class State
        {
            public ClothAllocator Allocator;
            public ClothLogHandler Log;
            public volatile IClothZoneListener Zones;
        }

        ClothWorldId id;
        GCHandle state;

        /// <summary>A world with every default (cloth_default_world_desc).</summary>
        public World() : this(ClothWorldDesc.Default(), null, null) { }

        /// <summary>
        /// Create a world from desc (start from ClothWorldDesc.Default()). An allocator or log handler
        /// given here replaces desc's Alloc, Free, Log and User; the host job system fields
        /// (EnqueueTask, FinishTask, TaskUser) pass through as they are.
        /// </summary>
        public World(ClothWorldDesc desc, ClothAllocator allocator = null, ClothLogHandler log = null)
        {
            var s = new State { Allocator = allocator, Log = log };
            state = GCHandle.Alloc(s);
            if (allocator != null)
            {
                desc.Alloc = Callbacks.AllocPointer;
                desc.Free = Callbacks.FreePointer;
                desc.User = GCHandle.ToIntPtr(state);
            }
            if (log != null)
            {
                desc.Log = Callbacks.LogPointer;
                desc.User = GCHandle.ToIntPtr(state);
            }
            ClothLibrary.Load();
            desc.EnsureDefaults();
            ClothResult r = Native.cloth_world_create(ref desc, out id);
            if (r != ClothResult.Ok)
            {
                string message = Native.cloth_get_last_error_str();
                state.Free();
                throw new ClothException(r, message);
            }
        }

        ~World() { Destroy(); }

        /// <summary>The native world; ObjectDisposedException after Dispose.</summary>
        public ClothWorldId Id { get { return Live; } }
        /// <summary>Whether the native world exists (false after Dispose).</summary>
        public bool IsValid { get { return !id.IsNull && Native.cloth_world_is_valid(id) != 0; } }
        /// <summary>Dispose was called (or the finalizer ran): every call now throws ObjectDisposedException.</summary>
        public bool IsDisposed { get { return id.IsNull; } }

        ClothWorldId Live
        {
            get
            {
                if (id.IsNull) throw new ObjectDisposedException("World");
                return id;
            }
        }

        public void Dispose()
        {
            Destroy();
            GC.SuppressFinalize(this);
        }

        void Destroy()
        {
            if (!id.IsNull)
            {
                Native.cloth_world_destroy(id);
                id = ClothWorldId.Null;
            }
            if (state.IsAllocated) state.Free();
        }

        /// <summary>
        /// Advance every cloth by dt seconds (cloth_step). Returns how the world advanced: Ok, or
        /// OverBudget, SolverFailed, NonfiniteState (that cloth was restored; ClothStats.LastStepResult
        /// says which) or OutOfMemory (the CG reference solver), whose message goes to the log handler.
        /// Throws ClothException when the world did not advance (a bad dt, ...): nothing moved.
        /// </summary>
        public ClothStepOutcome Step(float dt)
        {
            ClothResult r = Native.cloth_step(Live, dt);
            if (!IsStepOutcome(r)) throw new ClothException(r, Native.cloth_get_last_error_str());
            return (ClothStepOutcome)r;
        }

        internal static bool IsStepOutcome(ClothResult r)
        {
            return r == ClothResult.Ok || r == ClothResult.ErrorOverBudget || r == ClothResult.ErrorSolverFailed ||
                   r == ClothResult.ErrorNonfiniteState || r == ClothResult.ErrorOutOfMemory;
        }

        /// <summary>A grid fabric; `new ClothGridDesc { Columns = 8, Rows = 8 }` keeps every other default.</summary>
        public Fabric CreateGridFabric(ClothGridDesc desc)
        {
            desc.EnsureDefaults();
            ClothFabricId f;
            ClothException.Check(Native.cloth_fabric_create_grid(Live, ref desc, out f));
            return new Fabric(this, f);
        }

        /// <summary>A mesh fabric: 3 floats per vertex, 3 indices per triangle (copied during the call).</summary>
        public unsafe Fabric CreateMeshFabric(float[] positions, int[] indices,
                                              ClothSpringKind springKinds = ClothSpringKind.All)
        {
            if (positions == null) throw new ArgumentNullException("positions");
            if (positions.Length % 3 != 0) throw new ArgumentException("3 floats per vertex", "positions");
            fixed (float* p = positions)
            {
                return CreateMeshFabric(p, positions.Length / 3, indices, springKinds);
            }
        }

        /// <summary>A mesh fabric: one point per vertex, 3 indices per triangle (copied during the call).</summary>
        public unsafe Fabric CreateMeshFabric(Vector3[] positions, int[] indices,
                                              ClothSpringKind springKinds = ClothSpringKind.All)
        {
            if (positions == null) throw new ArgumentNullException("positions");
            fixed (Vector3* p = positions)
            {
                return CreateMeshFabric((float*)p, positions.Length, indices, springKinds);
            }
        }

        unsafe Fabric CreateMeshFabric(float* positions, int vertexCount, int[] indices, ClothSpringKind springKinds)
        {
            if (indices == null) throw new ArgumentNullException("indices");
            if (indices.Length % 3 != 0) throw new ArgumentException("3 indices per triangle", "indices");
            ClothMeshDesc desc = ClothMeshDesc.Default();
            desc.VertexCount = (uint)vertexCount;
            desc.TriangleCount = (uint)(indices.Length / 3);
            desc.SpringKinds = (uint)springKinds;
            ClothFabricId f;
            fixed (int* i = indices)
            {
                desc.Positions = (IntPtr)positions;
                desc.Indices = (IntPtr)i;
                ClothException.Check(Native.cloth_fabric_create_mesh(Live, ref desc, out f));
            }
            return new Fabric(this, f);
        }

        /// <summary>A fabric from a Wavefront OBJ file; the path is passed as UTF-8.</summary>
        public Fabric LoadObjFabric(string path, ClothSpringKind springKinds = ClothSpringKind.All)
        {
            if (path == null) throw new ArgumentNullException("path");
            ClothFabricId f;
            ClothException.Check(Native.cloth_fabric_create_obj(Live, path, (uint)springKinds, out f));
            return new Fabric(this, f);
        }

        /// <summary>A cloth from desc: `new ClothDesc { Fabric = fabric.Id }` keeps every other default.</summary>
        public Cloth CreateCloth(ClothDesc desc)
        {
            desc.EnsureDefaults();
            ClothId c;
            ClothException.Check(Native.cloth_create(Live, ref desc, out c));
            return new Cloth(this, c);
        }

        /// <summary>A cloth of fabric with every other default.</summary>
        public Cloth CreateCloth(Fabric fabric)
        {
            ClothDesc desc = ClothDesc.Default();
            desc.Fabric = fabric.Id;
            return CreateCloth(desc);
        }

        public Body CreateBody(ClothBodyDesc desc)
        {
            desc.EnsureDefaults();
            ClothBodyId b;
            ClothException.Check(Native.cloth_body_create(Live, ref desc, out b));
            var body = new Body(this, b);
            bodies[b] = body;
            return body;
        }

        // The Body owner of each live body id, for queries that return a body (Cloth.GetAttachment).
        readonly System.Collections.Generic.Dictionary<ClothBodyId, Body> bodies =
            new System.Collections.Generic.Dictionary<ClothBodyId, Body>();

        internal Body FindBody(ClothBodyId body)
        {
            Body b;
            return bodies.TryGetValue(body, out b) ? b : null;
        }
        internal void Forget(ClothBodyId body) { bodies.Remove(body); }

        /// <summary>A body at a pose (every other field default).</summary>
        public Body CreateBody(Float3 position, Float4 rotation)
        {
            ClothBodyDesc desc = ClothBodyDesc.Default();
            desc.Position = position;
            desc.Rotation = rotation;
            return CreateBody(desc);
        }

        ClothBodyId[] poseIds = new ClothBodyId[0];

        /// <summary>
        /// Many bodies' poses in one call (a character's bones each frame; cloth_world_set_body_poses):
        /// bodies[k] reaches positions[k] and rotations[k] at the end of the next step. Every entry is
        /// checked before any body moves. Reuses one id buffer: no allocation once it is large enough.
        /// </summary>
        public unsafe void SetBodyPoses(Body[] bodies, Vector3[] positions, Quaternion[] rotations)
        {
            if (bodies == null || positions == null || rotations == null) throw new ArgumentNullException("bodies");
            if (bodies.Length == 0 || positions.Length != bodies.Length || rotations.Length != bodies.Length)
                throw new ArgumentException("one position and one rotation per body, at least one body");
            if (poseIds.Length < bodies.Length) poseIds = new ClothBodyId[bodies.Length];
            for (int k = 0; k < bodies.Length; ++k)
            {
                if (bodies[k] == null) throw new ArgumentNullException("bodies");
                poseIds[k] = bodies[k].Id;
            }
            fixed (ClothBodyId* b = poseIds)
            fixed (Vector3* p = positions)
            fixed (Quaternion* q = rotations)
            {
                ClothException.Check(Native.cloth_world_set_body_poses(Live, b, (float*)p, (float*)q, (uint)bodies.Length));
            }
        }

        public Collider CreateSphere(ClothColliderDesc desc, float radius)
        {
            desc.EnsureDefaults();
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_sphere(Live, ref desc, radius, out c));
            return new Collider(this, c);
        }

        public Collider CreateCapsule(ClothColliderDesc desc, float radius, float halfHeight)
        {
            desc.EnsureDefaults();
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_capsule(Live, ref desc, radius, halfHeight, out c));
            return new Collider(this, c);
        }

        public Collider CreateTaperedCapsule(ClothColliderDesc desc, float bottomRadius, float topRadius, float halfHeight)
        {
            desc.EnsureDefaults();
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_tapered_capsule(Live, ref desc, bottomRadius, topRadius, halfHeight, out c));
            return new Collider(this, c);
        }

        public Collider CreateBox(ClothColliderDesc desc, Float3 halfExtents)
        {
            desc.EnsureDefaults();
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_box(Live, ref desc, ref halfExtents, out c));
            return new Collider(this, c);
        }

        public Collider CreatePlane(ClothColliderDesc desc, Float3 normal, float offset)
        {
            desc.EnsureDefaults();
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_plane(Live, ref desc, ref normal, offset, out c));
            return new Collider(this, c);
        }

        /// <summary>A convex hull of points (3 floats each).</summary>
        public Collider CreateConvexHull(ClothColliderDesc desc, float[] pointsXyz)
        {
            if (pointsXyz == null || pointsXyz.Length == 0) throw new ArgumentException("no points", "pointsXyz");
            desc.EnsureDefaults();
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_convex_hull(Live, ref desc, ref pointsXyz[0],
                                                                          (uint)(pointsXyz.Length / 3), out c));
            return new Collider(this, c);
        }

        /// <summary>A triangle mesh collider: 3 floats per vertex, 3 indices per triangle.</summary>
        public Collider CreateTriangleMesh(ClothColliderDesc desc, float[] verticesXyz, int[] indices)
        {
            if (verticesXyz == null || verticesXyz.Length == 0) throw new ArgumentException("no vertices", "verticesXyz");
            if (indices == null || indices.Length == 0) throw new ArgumentException("no indices", "indices");
            ClothColliderId c;
            desc.EnsureDefaults();
            ClothException.Check(Native.cloth_collider_create_triangle_mesh(
                Live, ref desc, ref verticesXyz[0], (uint)(verticesXyz.Length / 3), ref Reinterpret(indices)[0],
                (uint)(indices.Length / 3), out c));
            return new Collider(this, c);
        }

        /// <summary>A height field of heightfield.Columns x Rows heights (row-major; copied during the call).</summary>
        public unsafe Collider CreateHeightfield(ClothColliderDesc desc, ClothHeightfieldDesc heightfield,
                                                 float[] heights)
        {
            if (heights == null) throw new ArgumentNullException("heights");
            desc.EnsureDefaults();
            heightfield.EnsureDefaults();
            ClothColliderId c;
            fixed (float* h = heights)
            {
                heightfield.Heights = (IntPtr)h;
                ClothException.Check(Native.cloth_collider_create_heightfield(Live, ref desc, ref heightfield, out c));
            }
            return new Collider(this, c);
        }

        public void SetGravity(Float3 gravity) { ClothException.Check(Native.cloth_world_set_gravity(Live, ref gravity)); }
        public void ShiftOrigin(Float3 shift) { ClothException.Check(Native.cloth_world_shift_origin(Live, ref shift)); }
        public void SetWorkerSpin(int microseconds)
        {
            if (microseconds < 0) throw new ArgumentOutOfRangeException("microseconds");
            ClothException.Check(Native.cloth_world_set_worker_spin(Live, (uint)microseconds));
        }
        public void SetFrameBudget(float milliseconds) { ClothException.Check(Native.cloth_world_set_frame_budget(Live, milliseconds)); }
        /// <summary>The viewer whose distance scales each cloth's importance under a frame budget.</summary>
        public void SetViewer(Float3 position) { ClothException.Check(Native.cloth_world_set_viewer(Live, ref position)); }
        public unsafe void ClearViewer() { ClothException.Check(Native.cloth_world_set_viewer(Live, (Float3*)null)); }
        public void SetProfiling(int maxTasksPerFrame)
        {
            if (maxTasksPerFrame < 0) throw new ArgumentOutOfRangeException("maxTasksPerFrame");
            ClothException.Check(Native.cloth_world_set_profiling(Live, (uint)maxTasksPerFrame));
        }

        /// <summary>int[] as the uint[] of the C API (the same bits; a negative index is out of range there).</summary>
        internal static uint[] Reinterpret(int[] indices)
        {
            return (uint[])(object)indices;
        }

        /// <summary>
        /// The last step's profile into a struct the caller keeps and reuses: the profile is about
        /// 4 KB of inline arrays (read them with GetStageMs(i), GetWorkerBusyMs(i), ...), so it is
        /// filled in place, never copied per call. Sets profile.StructSize.
        /// </summary>
        public void GetFrameProfile(ref ClothFrameProfile profile)
        {
            profile.StructSize = (uint)Marshal.SizeOf(typeof(ClothFrameProfile));
            ClothException.Check(Native.cloth_world_get_frame_profile(Live, ref profile));
        }

        /// <summary>The last frame's task records, at most records.Length; returns how many were copied.</summary>
        public int ReadTaskRecords(ClothTaskRecord[] records)
        {
            if (records == null || records.Length == 0) return 0;
            uint count;
            ClothException.Check(Native.cloth_world_read_task_records(Live, out records[0], (uint)records.Length, out count));
            return (int)count;
        }

        /// <summary>The last frame as Chrome trace-event JSON.</summary>
        public unsafe string WriteTraceJson()
        {
            UIntPtr size;
            ClothException.Check(Native.cloth_world_write_trace_json(Live, null, UIntPtr.Zero, &size));
            var buffer = new byte[(int)(ulong)size];
            ClothException.Check(Native.cloth_world_write_trace_json(Live, ref buffer[0], size, out size));
            return System.Text.Encoding.UTF8.GetString(buffer, 0, buffer.Length - 1);
        }

        /// <summary>Install zone callbacks (null removes them). The listener is called from worker threads.</summary>
        public void SetZoneCallbacks(IClothZoneListener listener)
        {
            ClothWorldId live = Live;
            var s = (State)state.Target;
            if (listener == null)
            {
                ClothException.Check(Native.cloth_world_set_zone_callbacks(live, IntPtr.Zero, IntPtr.Zero, IntPtr.Zero));
                s.Zones = null;
                return;
            }
            s.Zones = listener;
            ClothException.Check(Native.cloth_world_set_zone_callbacks(live, Callbacks.ZoneBeginPointer,
                                                                       Callbacks.ZoneEndPointer,
                                                                       GCHandle.ToIntPtr(state)));
        }

        // The static callbacks (IL2CPP: no instance methods, no closures; state through `user`). Their
        // delegates live in static fields, so the function pointers stay valid for the process.
        static class Callbacks
        {
            static readonly ClothAllocFn alloc = Alloc;
            static readonly ClothFreeFn free = Free;
            static readonly ClothLogFn log = Log;
            static readonly ClothZoneBeginFn zoneBegin = ZoneBegin;
            static readonly ClothZoneEndFn zoneEnd = ZoneEnd;
            public static readonly IntPtr AllocPointer = Marshal.GetFunctionPointerForDelegate(alloc);
            public static readonly IntPtr FreePointer = Marshal.GetFunctionPointerForDelegate(free);
            public static readonly IntPtr LogPointer = Marshal.GetFunctionPointerForDelegate(log);
            public static readonly IntPtr ZoneBeginPointer = Marshal.GetFunctionPointerForDelegate(zoneBegin);
            public static readonly IntPtr ZoneEndPointer = Marshal.GetFunctionPointerForDelegate(zoneEnd);

            static State Of(IntPtr user) { return (State)GCHandle.FromIntPtr(user).Target; }

            [MonoPInvokeCallback(typeof(ClothAllocFn))]
            static IntPtr Alloc(UIntPtr size, UIntPtr alignment, IntPtr user)
            {
                try { return Of(user).Allocator.Allocate((ulong)size, (ulong)alignment); }
                catch (Exception) { return IntPtr.Zero; }
            }

            [MonoPInvokeCallback(typeof(ClothFreeFn))]
            static void Free(IntPtr pointer, UIntPtr size, IntPtr user)
            {
                try { Of(user).Allocator.Free(pointer, (ulong)size); }
                catch (Exception) { }
            }

            [MonoPInvokeCallback(typeof(ClothLogFn))]
            static void Log(ClothLogLevel level, ClothResult code, IntPtr message, IntPtr user)
            {
                try
                {
                    // An error ClothSharp throws is not logged as well (the exception carries its
                    // message); the step outcomes World.Step returns instead of throwing are.
                    if (level == ClothLogLevel.Error && !IsStepOutcome(code)) return;
                    ClothLogHandler handler = Of(user).Log;
                    if (handler != null) handler(level, code, Utf8.ToString(message));
                }
                catch (Exception) { }
            }

            [MonoPInvokeCallback(typeof(ClothZoneBeginFn))]
            static void ZoneBegin(IntPtr name, uint worker, IntPtr user)
            {
                try
                {
                    IClothZoneListener zones = Of(user).Zones;
                    if (zones != null) zones.Begin(StaticNames.Get(name), (int)worker);
                }
                catch (Exception) { }
            }

            [MonoPInvokeCallback(typeof(ClothZoneEndFn))]
            static void ZoneEnd(IntPtr name, uint worker, IntPtr user)
            {
                try
                {
                    IClothZoneListener zones = Of(user).Zones;
                    if (zones != null) zones.End(StaticNames.Get(name), (int)worker);
                }
                catch (Exception) { }
            }
        }
    }

    /// <summary>
    /// An object inside a world. Dispose destroys it; after its world is disposed it is already gone
    /// (IsDisposed is then true) and Dispose does nothing. Every member of a disposed object throws
    /// ObjectDisposedException. No finalizer: destroying from the finalizer thread would call a world
    /// while its own thread may be using it (cloth.h's threading contract); the world frees everything
    /// it holds when it is destroyed.
    /// </summary>
    public abstract class WorldObject : IDisposable
    {
        bool disposed;

        protected WorldObject(World world) { World = world; }
        public World World { get; private set; }
        /// <summary>Disposed, or its world is.</summary>
        public bool IsDisposed { get { return disposed || World.IsDisposed; } }

        public void Dispose()
        {
            if (disposed) return;
            disposed = true;
            if (World.IsDisposed) return;
            ClothResult r = Destroy();
            // Already gone with what it was fixed to (a collider with its body): nothing to do.
            if (r != ClothResult.Ok && r != ClothResult.ErrorInvalidHandle) ClothException.Check(r);
        }

        /// <summary>Throws ObjectDisposedException when IsDisposed.</summary>
        protected void ThrowIfDisposed()
        {
            if (IsDisposed)
            {
                throw new ObjectDisposedException(GetType().Name, disposed ? null : "its World was disposed");
            }
        }

        protected abstract ClothResult Destroy();
    }

    /// <summary>Shared topology (cloth_fabric_id). Disposing releases the handle; cloths made of it keep working.</summary>
    public sealed partial class Fabric : WorldObject
    {
        readonly ClothFabricId id;
        internal Fabric(World world, ClothFabricId id) : base(world) { this.id = id; }
        /// <summary>The native fabric; ObjectDisposedException once disposed.</summary>
        public ClothFabricId Id { get { ThrowIfDisposed(); return id; } }
        protected override ClothResult Destroy() { return Native.cloth_fabric_destroy(id); }

        public int ParticleCount
        {
            get { uint n; ClothException.Check(Native.cloth_fabric_get_particle_count(Id, out n)); return (int)n; }
        }
        public int TriangleCount
        {
            get { uint n; ClothException.Check(Native.cloth_fabric_get_triangle_count(Id, out n)); return (int)n; }
        }
        public int SpringCount(ClothSpringKind kinds)
        {
            uint n;
            ClothException.Check(Native.cloth_fabric_get_spring_count(Id, (uint)kinds, out n));
            return (int)n;
        }
        /// <summary>3 indices per triangle into indices (at least 3 * TriangleCount).</summary>
        public void ReadTriangles(int[] indices)
        {
            if (indices == null || indices.Length == 0) throw new ArgumentException("empty buffer", "indices");
            ClothException.Check(Native.cloth_fabric_read_triangles(Id, out World.Reinterpret(indices)[0], (uint)indices.Length));
        }
    }

    /// <summary>A rigid frame the host moves (cloth_body_id). Disposing destroys its colliders and attachments too.</summary>
    public sealed partial class Body : WorldObject
    {
        readonly ClothBodyId id;
        internal Body(World world, ClothBodyId id) : base(world) { this.id = id; }
        /// <summary>The native body; ObjectDisposedException once disposed.</summary>
        public ClothBodyId Id { get { ThrowIfDisposed(); return id; } }
        protected override ClothResult Destroy()
        {
            World.Forget(id);
            return Native.cloth_body_destroy(id);
        }

        /// <summary>
        /// The pose reached at the end of the next step (rotation: unit quaternion x, y, z, w). Takes
        /// Float3/Float4 and System.Numerics' (or Unity's) Vector3/Quaternion.
        /// </summary>
        public void SetPose(Float3 position, Float4 rotation)
        {
            ClothException.Check(Native.cloth_body_set_pose(Id, ref position, ref rotation));
        }
        public void Teleport(Float3 position, Float4 rotation)
        {
            ClothException.Check(Native.cloth_body_teleport(Id, ref position, ref rotation));
        }
        public void SetVelocity(Float3 linear, Float3 angular)
        {
            ClothException.Check(Native.cloth_body_set_velocity(Id, ref linear, ref angular));
        }
        public void GetPose(out Float3 position, out Float4 rotation)
        {
            ClothException.Check(Native.cloth_body_get_pose(Id, out position, out rotation));
        }
        public void GetPose(out Vector3 position, out Quaternion rotation)
        {
            Float3 p;
            Float4 q;
            GetPose(out p, out q);
            position = p;
            rotation = q;
        }
#if UNITY_5_3_OR_NEWER
        public void GetPose(out UnityEngine.Vector3 position, out UnityEngine.Quaternion rotation)
        {
            Float3 p;
            Float4 q;
            GetPose(out p, out q);
            position = p;
            rotation = q;
        }
#endif
        /// <summary>The position set last.</summary>
        public Vector3 Position { get { Float3 p; Float4 q; GetPose(out p, out q); return p; } }
        /// <summary>The rotation set last.</summary>
        public Quaternion Rotation { get { Float3 p; Float4 q; GetPose(out p, out q); return q; } }
    }

    /// <summary>A collision shape (cloth_collider_id); it dies with the body it is fixed to.</summary>
    public sealed partial class Collider : WorldObject
    {
        readonly ClothColliderId id;
        internal Collider(World world, ClothColliderId id) : base(world) { this.id = id; }
        /// <summary>The native collider; ObjectDisposedException once disposed.</summary>
        public ClothColliderId Id { get { ThrowIfDisposed(); return id; } }
        protected override ClothResult Destroy() { return Native.cloth_collider_destroy(id); }
        public void SetGroupBits(uint bits) { ClothException.Check(Native.cloth_collider_set_group_bits(Id, bits)); }
    }

    /// <summary>
    /// One simulated cloth (cloth_id). Particle data comes in float arrays and spans (3 floats per
    /// particle), Float3, System.Numerics.Vector3 (and under Unity, UnityEngine.Vector3) arrays and
    /// spans; particle indices are int.
    /// </summary>
    public sealed unsafe partial class Cloth : WorldObject
    {
        readonly ClothId id;

        internal Cloth(World world, ClothId id) : base(world)
        {
            this.id = id;
            uint n;
            ClothException.Check(Native.cloth_get_particle_count(id, out n));
            ParticleCount = (int)n;
        }

        /// <summary>The native cloth; ObjectDisposedException once disposed (or its world is).</summary>
        public ClothId Id { get { ThrowIfDisposed(); return id; } }
        /// <summary>Particles of the cloth; particle data holds 3 * ParticleCount floats.</summary>
        public int ParticleCount { get; private set; }
        protected override ClothResult Destroy() { return Native.cloth_destroy(id); }

        // Particle data ------------------------------------------------------------------------------
        // Every overload pins its buffer and makes one native call; a buffer shorter than the cloth
        // is refused by the library (ClothException, ErrorInvalidCount), nothing read.

        enum Data { Positions, Velocities, Normals }

        void Read(Data data, float* xyz, int floats)
        {
            ClothId c = Id;
            uint n = (uint)floats;
            switch (data)
            {
                case Data.Positions: ClothException.Check(Native.cloth_read_positions(c, xyz, n)); break;
                case Data.Velocities: ClothException.Check(Native.cloth_read_velocities(c, xyz, n)); break;
                default: ClothException.Check(Native.cloth_read_normals(c, xyz, n)); break;
            }
        }
        void Read(Data data, float[] xyz, int offset)
        {
            CheckBuffer(xyz, offset);
            fixed (float* p = xyz) { Read(data, p + offset, xyz.Length - offset); }
        }
        void Read(Data data, Float3[] v)
        {
            CheckBuffer(v, 0);
            fixed (Float3* p = v) { Read(data, (float*)p, 3 * v.Length); }
        }
        void Read(Data data, Vector3[] v)
        {
            CheckBuffer(v, 0);
            fixed (Vector3* p = v) { Read(data, (float*)p, 3 * v.Length); }
        }

        public void ReadPositions(float[] xyz) { Read(Data.Positions, xyz, 0); }
        /// <summary>Positions into xyz from offset on (3 floats per particle).</summary>
        public void ReadPositions(float[] xyz, int offset) { Read(Data.Positions, xyz, offset); }
        /// <summary>Positions into one Float3 per particle.</summary>
        public void ReadPositions(Float3[] vertices) { Read(Data.Positions, vertices); }
        /// <summary>Positions into one System.Numerics.Vector3 per particle.</summary>
        public void ReadPositions(Vector3[] vertices) { Read(Data.Positions, vertices); }
        public void ReadVelocities(float[] xyz) { Read(Data.Velocities, xyz, 0); }
        public void ReadVelocities(Float3[] velocities) { Read(Data.Velocities, velocities); }
        public void ReadVelocities(Vector3[] velocities) { Read(Data.Velocities, velocities); }
        public void ReadNormals(float[] xyz) { Read(Data.Normals, xyz, 0); }
        public void ReadNormals(float[] xyz, int offset) { Read(Data.Normals, xyz, offset); }
        public void ReadNormals(Float3[] normals) { Read(Data.Normals, normals); }
        public void ReadNormals(Vector3[] normals) { Read(Data.Normals, normals); }
#if UNITY_5_3_OR_NEWER
        /// <summary>Positions straight into a Unity vertex array (Mesh.SetVertices), no copy.</summary>
        public void ReadPositions(UnityEngine.Vector3[] vertices)
        {
            CheckBuffer(vertices, 0);
            fixed (UnityEngine.Vector3* p = vertices) { Read(Data.Positions, (float*)p, 3 * vertices.Length); }
        }
        /// <summary>Normals straight into a Unity normal array (Mesh.SetNormals), no copy.</summary>
        public void ReadNormals(UnityEngine.Vector3[] normals)
        {
            CheckBuffer(normals, 0);
            fixed (UnityEngine.Vector3* p = normals) { Read(Data.Normals, (float*)p, 3 * normals.Length); }
        }
#endif

        static void CheckBuffer(Array buffer, int offset)
        {
            if (buffer == null) throw new ArgumentNullException("buffer");
            if (offset < 0 || offset >= buffer.Length) throw new ArgumentOutOfRangeException("offset");
        }

        // Particle writes: one pointer core, array and span overloads around it.

        static void RequireIndices(int count)
        {
            if (count == 0) throw new ArgumentException("no particle indices");
        }
        static void RequirePoints(int indices, int points)
        {
            RequireIndices(indices);
            if (points != indices) throw new ArgumentException("one point (3 floats) per index");
        }

        void SetPositions(int* indices, float* xyz, int count)
        {
            ClothException.Check(Native.cloth_set_positions(Id, (uint*)indices, xyz, (uint)count));
        }
        void Pin(int* indices, int count) { ClothException.Check(Native.cloth_pin(Id, (uint*)indices, (uint)count)); }
        void Unpin(int* indices, int count) { ClothException.Check(Native.cloth_unpin(Id, (uint*)indices, (uint)count)); }
        void SetPinTargets(int* indices, float* xyz, int count)
        {
            ClothException.Check(Native.cloth_set_pin_targets(Id, (uint*)indices, xyz, (uint)count));
        }
        void Attach(Body body, int* indices, float* offsets, int count)
        {
            if (body == null) throw new ArgumentNullException("body");
            ClothException.Check(Native.cloth_attach(Id, body.Id, (uint*)indices, offsets, (uint)count));
        }
        void Detach(int* indices, int count) { ClothException.Check(Native.cloth_detach(Id, (uint*)indices, (uint)count)); }

        /// <summary>Teleport particles to positions (3 floats each); their velocities become zero.</summary>
        public void SetPositions(int[] indices, float[] xyz)
        {
            RequireSome(indices);
            RequirePoints(indices.Length, xyz == null ? -1 : (xyz.Length % 3 == 0 ? xyz.Length / 3 : -1));
            fixed (int* i = indices) fixed (float* p = xyz) { SetPositions(i, p, indices.Length); }
        }
        /// <summary>Teleport particles to positions; their velocities become zero.</summary>
        public void SetPositions(int[] indices, Vector3[] positions)
        {
            RequireSome(indices);
            RequirePoints(indices.Length, positions == null ? -1 : positions.Length);
            fixed (int* i = indices) fixed (Vector3* p = positions) { SetPositions(i, (float*)p, indices.Length); }
        }
        public void Pin(int[] indices)
        {
            RequireSome(indices);
            fixed (int* i = indices) { Pin(i, indices.Length); }
        }
        public void Unpin(int[] indices)
        {
            RequireSome(indices);
            fixed (int* i = indices) { Unpin(i, indices.Length); }
        }
        /// <summary>Where pinned particles arrive at the end of the next step (3 floats each).</summary>
        public void SetPinTargets(int[] indices, float[] xyz)
        {
            RequireSome(indices);
            RequirePoints(indices.Length, xyz == null ? -1 : (xyz.Length % 3 == 0 ? xyz.Length / 3 : -1));
            fixed (int* i = indices) fixed (float* p = xyz) { SetPinTargets(i, p, indices.Length); }
        }
        /// <summary>Where pinned particles arrive at the end of the next step.</summary>
        public void SetPinTargets(int[] indices, Vector3[] targets)
        {
            RequireSome(indices);
            RequirePoints(indices.Length, targets == null ? -1 : targets.Length);
            fixed (int* i = indices) fixed (Vector3* p = targets) { SetPinTargets(i, (float*)p, indices.Length); }
        }
        /// <summary>Attach particles to body where they are now relative to it.</summary>
        public void Attach(Body body, int[] indices) { Attach(body, indices, (float[])null); }
        /// <summary>Attach particles to body at body-local offsets (3 floats each), or (offsets null) where they are now.</summary>
        public void Attach(Body body, int[] indices, float[] localOffsetsXyz)
        {
            RequireSome(indices);
            if (localOffsetsXyz != null)
                RequirePoints(indices.Length, localOffsetsXyz.Length % 3 == 0 ? localOffsetsXyz.Length / 3 : -1);
            fixed (int* i = indices) fixed (float* o = localOffsetsXyz) { Attach(body, i, o, indices.Length); }
        }
        /// <summary>Attach particles to body at body-local offsets, or (offsets null) where they are now.</summary>
        public void Attach(Body body, int[] indices, Vector3[] localOffsets)
        {
            RequireSome(indices);
            if (localOffsets != null) RequirePoints(indices.Length, localOffsets.Length);
            fixed (int* i = indices) fixed (Vector3* o = localOffsets) { Attach(body, i, (float*)o, indices.Length); }
        }
        public void Detach(int[] indices)
        {
            RequireSome(indices);
            fixed (int* i = indices) { Detach(i, indices.Length); }
        }
        /// <summary>Masses (kg) of the particles at indices.</summary>
        public void SetParticleMasses(int[] indices, float[] masses)
        {
            RequireSome(indices);
            if (masses == null || masses.Length != indices.Length) throw new ArgumentException("one mass per index");
            fixed (int* i = indices) fixed (float* m = masses)
            {
                ClothException.Check(Native.cloth_set_particle_masses(Id, (uint*)i, m, (uint)indices.Length));
            }
        }
        /// <summary>Every particle's mass (kg) into masses (at least ParticleCount).</summary>
        public void ReadParticleMasses(float[] masses)
        {
            RequireSome(masses);
            fixed (float* m = masses) { ClothException.Check(Native.cloth_read_particle_masses(Id, m, (uint)masses.Length)); }
        }
        public void RestoreSnapshot(byte[] snapshot)
        {
            RequireSome(snapshot);
            fixed (byte* p = snapshot)
            {
                ClothException.Check(Native.cloth_restore_snapshot(Id, (IntPtr)p, (UIntPtr)(ulong)snapshot.Length));
            }
        }

#if !CLOTH_NO_SPAN
        public void ReadPositions(Span<float> xyz) { fixed (float* p = &MemoryMarshal.GetReference(xyz)) { Read(Data.Positions, p, xyz.Length); } }
        public void ReadPositions(Span<Vector3> v) { fixed (Vector3* p = &MemoryMarshal.GetReference(v)) { Read(Data.Positions, (float*)p, 3 * v.Length); } }
        public void ReadVelocities(Span<float> xyz) { fixed (float* p = &MemoryMarshal.GetReference(xyz)) { Read(Data.Velocities, p, xyz.Length); } }
        public void ReadVelocities(Span<Vector3> v) { fixed (Vector3* p = &MemoryMarshal.GetReference(v)) { Read(Data.Velocities, (float*)p, 3 * v.Length); } }
        public void ReadNormals(Span<float> xyz) { fixed (float* p = &MemoryMarshal.GetReference(xyz)) { Read(Data.Normals, p, xyz.Length); } }
        public void ReadNormals(Span<Vector3> v) { fixed (Vector3* p = &MemoryMarshal.GetReference(v)) { Read(Data.Normals, (float*)p, 3 * v.Length); } }

        /// <summary>Teleport particles to positions (3 floats each); their velocities become zero.</summary>
        public void SetPositions(ReadOnlySpan<int> indices, ReadOnlySpan<float> xyz)
        {
            RequirePoints(indices.Length, xyz.Length % 3 == 0 ? xyz.Length / 3 : -1);
            fixed (int* i = &MemoryMarshal.GetReference(indices)) fixed (float* p = &MemoryMarshal.GetReference(xyz))
            {
                SetPositions(i, p, indices.Length);
            }
        }
        public void SetPositions(ReadOnlySpan<int> indices, ReadOnlySpan<Vector3> positions)
        {
            RequirePoints(indices.Length, positions.Length);
            fixed (int* i = &MemoryMarshal.GetReference(indices)) fixed (Vector3* p = &MemoryMarshal.GetReference(positions))
            {
                SetPositions(i, (float*)p, indices.Length);
            }
        }
        public void Pin(ReadOnlySpan<int> indices)
        {
            RequireIndices(indices.Length);
            fixed (int* i = &MemoryMarshal.GetReference(indices)) { Pin(i, indices.Length); }
        }
        public void Unpin(ReadOnlySpan<int> indices)
        {
            RequireIndices(indices.Length);
            fixed (int* i = &MemoryMarshal.GetReference(indices)) { Unpin(i, indices.Length); }
        }
        /// <summary>Where pinned particles arrive at the end of the next step (3 floats each).</summary>
        public void SetPinTargets(ReadOnlySpan<int> indices, ReadOnlySpan<float> xyz)
        {
            RequirePoints(indices.Length, xyz.Length % 3 == 0 ? xyz.Length / 3 : -1);
            fixed (int* i = &MemoryMarshal.GetReference(indices)) fixed (float* p = &MemoryMarshal.GetReference(xyz))
            {
                SetPinTargets(i, p, indices.Length);
            }
        }
        public void SetPinTargets(ReadOnlySpan<int> indices, ReadOnlySpan<Vector3> targets)
        {
            RequirePoints(indices.Length, targets.Length);
            fixed (int* i = &MemoryMarshal.GetReference(indices)) fixed (Vector3* p = &MemoryMarshal.GetReference(targets))
            {
                SetPinTargets(i, (float*)p, indices.Length);
            }
        }
        /// <summary>
        /// Attach particles to body at body-local offsets (3 floats each), or, with no offsets, where
        /// they are now relative to the body.
        /// </summary>
        public void Attach(Body body, ReadOnlySpan<int> indices, ReadOnlySpan<float> localOffsetsXyz)
        {
            RequireIndices(indices.Length);
            if (localOffsetsXyz.Length != 0)
                RequirePoints(indices.Length, localOffsetsXyz.Length % 3 == 0 ? localOffsetsXyz.Length / 3 : -1);
            fixed (int* i = &MemoryMarshal.GetReference(indices)) fixed (float* o = &MemoryMarshal.GetReference(localOffsetsXyz))
            {
                Attach(body, i, localOffsetsXyz.Length == 0 ? null : o, indices.Length);
            }
        }
        public void Detach(ReadOnlySpan<int> indices)
        {
            RequireIndices(indices.Length);
            fixed (int* i = &MemoryMarshal.GetReference(indices)) { Detach(i, indices.Length); }
        }
        public void SetParticleMasses(ReadOnlySpan<int> indices, ReadOnlySpan<float> masses)
        {
            RequireIndices(indices.Length);
            if (masses.Length != indices.Length) throw new ArgumentException("one mass per index");
            fixed (int* i = &MemoryMarshal.GetReference(indices)) fixed (float* m = &MemoryMarshal.GetReference(masses))
            {
                ClothException.Check(Native.cloth_set_particle_masses(Id, (uint*)i, m, (uint)indices.Length));
            }
        }
        public void ReadParticleMasses(Span<float> masses)
        {
            fixed (float* m = &MemoryMarshal.GetReference(masses))
            {
                ClothException.Check(Native.cloth_read_particle_masses(Id, m, (uint)masses.Length));
            }
        }
        /// <summary>Restore a snapshot (exactly the bytes SaveSnapshot wrote).</summary>
        public void RestoreSnapshot(ReadOnlySpan<byte> snapshot)
        {
            fixed (byte* p = &MemoryMarshal.GetReference(snapshot))
            {
                ClothException.Check(Native.cloth_restore_snapshot(Id, (IntPtr)p, (UIntPtr)(ulong)snapshot.Length));
            }
        }
#endif

        static void RequireSome(Array a)
        {
            if (a == null || a.Length == 0) throw new ArgumentException("an empty or null array");
        }

        // Character cloth: skin, joint matrices, max distances, backstops (cloth.h "Character cloth").

        /// <summary>
        /// Bind the cloth to jointCount joints (replacing any skin): `influences` (1..4) joint indices
        /// per particle in joints (by vertex, ParticleCount * influences), and as many weights, each
        /// particle's summing to 1 (weights null with influences 1). The joint matrices start as
        /// identities. Copied during the call.
        /// </summary>
        public void SetSkin(int jointCount, int influences, int[] joints, float[] weights)
        {
            if (joints == null) throw new ArgumentNullException("joints");
            fixed (int* j = joints) fixed (float* w = weights)
            {
                SetSkin(jointCount, influences, j, joints.Length, w, weights == null ? 0 : weights.Length);
            }
        }
#if !CLOTH_NO_SPAN
        public void SetSkin(int jointCount, int influences, ReadOnlySpan<int> joints, ReadOnlySpan<float> weights)
        {
            fixed (int* j = &MemoryMarshal.GetReference(joints)) fixed (float* w = &MemoryMarshal.GetReference(weights))
            {
                SetSkin(jointCount, influences, j, joints.Length, weights.Length == 0 ? null : w, weights.Length);
            }
        }
#endif
        void SetSkin(int jointCount, int influences, int* joints, int jointEntries, float* weights, int weightEntries)
        {
            if (jointCount <= 0 || influences <= 0) throw new ArgumentOutOfRangeException("jointCount");
            if (jointEntries != ParticleCount * influences) throw new ArgumentException("ParticleCount * influences joint indices");
            if (weights != null && weightEntries != jointEntries) throw new ArgumentException("one weight per joint index");
            ClothSkinDesc desc = ClothSkinDesc.Default();
            desc.ParticleCount = (uint)ParticleCount;
            desc.JointCount = (uint)jointCount;
            desc.Influences = (uint)influences;
            desc.Joints = (IntPtr)joints;
            desc.Weights = (IntPtr)weights;
            ClothException.Check(Native.cloth_set_skin(Id, ref desc));
        }

        /// <summary>
        /// This frame's joint matrices (at least the skin's joint count), as System.Numerics keeps
        /// them: row vectors, translation in M41..M43, whose memory is the column-major 4x4 the
        /// library reads. Matrix4x4.CreateTranslation(0, 1, 0) moves the skin up by 1.
        /// </summary>
        public void SetJointMatrices(Matrix4x4[] matrices)
        {
            RequireSome(matrices);
            fixed (Matrix4x4* m = matrices) { SetJointMatrices((float*)m, matrices.Length, ClothMatrixLayout.ColumnMajor4x4); }
        }
#if !CLOTH_NO_SPAN
        public void SetJointMatrices(ReadOnlySpan<Matrix4x4> matrices)
        {
            fixed (Matrix4x4* m = &MemoryMarshal.GetReference(matrices))
            {
                SetJointMatrices((float*)m, matrices.Length, ClothMatrixLayout.ColumnMajor4x4);
            }
        }
#endif
#if UNITY_5_3_OR_NEWER
        /// <summary>Unity's matrices (column-major, column vectors: Transform.localToWorldMatrix * bindpose), as they are.</summary>
        public void SetJointMatrices(UnityEngine.Matrix4x4[] matrices)
        {
            RequireSome(matrices);
            fixed (UnityEngine.Matrix4x4* m = matrices)
            {
                SetJointMatrices((float*)m, matrices.Length, ClothMatrixLayout.ColumnMajor4x4);
            }
        }
#endif
        /// <summary>Joint matrices as floats in `layout` (16 per matrix column-major, or 12 per matrix row-major 3x4).</summary>
        public void SetJointMatrices(float[] matrices, ClothMatrixLayout layout)
        {
            RequireSome(matrices);
            int per = layout == ClothMatrixLayout.RowMajor3x4 ? 12 : 16;
            if (matrices.Length % per != 0) throw new ArgumentException(per + " floats per matrix", "matrices");
            fixed (float* m = matrices) { SetJointMatrices(m, matrices.Length / per, layout); }
        }
        void SetJointMatrices(float* matrices, int count, ClothMatrixLayout layout)
        {
            ClothException.Check(Native.cloth_set_joint_matrices(Id, matrices, (uint)count, layout));
        }

        /// <summary>Positions and normals the host skinned (one each per particle), for the end of the next step.</summary>
        public void SetSkinnedPositions(Vector3[] positions, Vector3[] normals)
        {
            if (positions == null || normals == null) throw new ArgumentNullException("positions");
            if (normals.Length != positions.Length) throw new ArgumentException("one normal per position");
            fixed (Vector3* p = positions) fixed (Vector3* n = normals)
            {
                ClothException.Check(Native.cloth_set_skinned_positions(Id, (float*)p, (float*)n, (uint)positions.Length));
            }
        }
        /// <summary>The skinned positions (and normals, unless null) of the last step's end.</summary>
        public void ReadSkinnedPositions(Vector3[] positions, Vector3[] normals = null)
        {
            RequireSome(positions);
            if (normals != null && normals.Length != positions.Length) throw new ArgumentException("one normal per position");
            fixed (Vector3* p = positions) fixed (Vector3* n = normals)
            {
                ClothException.Check(Native.cloth_read_skinned_positions(Id, (float*)p, (float*)n, (uint)(3 * positions.Length)));
            }
        }
        /// <summary>
        /// Every particle's max distance (m) from its skinned position: float.PositiveInfinity for none,
        /// 0 pins it to the skin. The cloth needs a skin.
        /// </summary>
        public void SetMaxDistances(float[] distances)
        {
            RequireSome(distances);
            fixed (float* d = distances) { ClothException.Check(Native.cloth_set_max_distances(Id, d, (uint)distances.Length)); }
        }
        /// <summary>Every particle's backstop sphere: distance behind the skin along its normal, and radius (0, 0: none).</summary>
        public void SetBackstops(float[] distances, float[] radii)
        {
            RequireSome(distances);
            if (radii == null || radii.Length != distances.Length) throw new ArgumentException("one radius per distance");
            fixed (float* d = distances) fixed (float* r = radii)
            {
                ClothException.Check(Native.cloth_set_backstops(Id, d, r, (uint)distances.Length));
            }
        }
#if !CLOTH_NO_SPAN
        public void SetMaxDistances(ReadOnlySpan<float> distances)
        {
            fixed (float* d = &MemoryMarshal.GetReference(distances))
            {
                ClothException.Check(Native.cloth_set_max_distances(Id, d, (uint)distances.Length));
            }
        }
        public void SetBackstops(ReadOnlySpan<float> distances, ReadOnlySpan<float> radii)
        {
            if (radii.Length != distances.Length) throw new ArgumentException("one radius per distance");
            fixed (float* d = &MemoryMarshal.GetReference(distances)) fixed (float* r = &MemoryMarshal.GetReference(radii))
            {
                ClothException.Check(Native.cloth_set_backstops(Id, d, r, (uint)distances.Length));
            }
        }
#endif

        // Settings and queries -----------------------------------------------------------------------
        // The get/set properties of one shape (Solver, Importance, ...) are generated: ClothSharp.g.cs.

        public bool IsPinned(int index)
        {
            if (index < 0) throw new ArgumentOutOfRangeException("index");
            byte pinned;
            ClothException.Check(Native.cloth_is_pinned(Id, (uint)index, out pinned));
            return pinned != 0;
        }
        public bool IsSleeping
        {
            get { byte b; ClothException.Check(Native.cloth_is_sleeping(Id, out b)); return b != 0; }
        }
        public bool Teleported
        {
            get { byte b; ClothException.Check(Native.cloth_get_teleported(Id, out b)); return b != 0; }
        }
        /// <summary>Put the cloth to sleep now (out of view): it costs nothing and keeps its motion for Wake.</summary>
        public void Sleep() { ClothException.Check(Native.cloth_sleep(Id)); }
        public void Wake() { ClothException.Check(Native.cloth_wake(Id)); }

        /// <summary>The body the particle is attached to (null if none) and its body-local offset.</summary>
        public Body GetAttachment(int index, out Vector3 localOffset)
        {
            if (index < 0) throw new ArgumentOutOfRangeException("index");
            ClothBodyId body;
            Float3 offset;
            ClothException.Check(Native.cloth_get_attachment(Id, (uint)index, out body, out offset));
            localOffset = offset;
            return body.IsNull ? null : World.FindBody(body);
        }

        public ClothStats GetStats()
        {
            ClothStats stats = ClothStats.Default();
            ClothException.Check(Native.cloth_get_stats(Id, ref stats));
            return stats;
        }
        public ClothSelfCollisionStats GetSelfCollisionStats()
        {
            ClothSelfCollisionStats s = ClothSelfCollisionStats.Default();
            ClothException.Check(Native.cloth_get_self_collision_stats(Id, ref s));
            return s;
        }
        /// <summary>
        /// Contact with another cloth of the same world (garments worn together): `new
        /// ClothClothContactDesc { Enabled = true, Thickness = 0.01f }`; Enabled = false turns it off.
        /// </summary>
        public void SetContactWith(Cloth other, ClothClothContactDesc desc)
        {
            if (other == null) throw new ArgumentNullException("other");
            desc.EnsureDefaults();
            ClothException.Check(Native.cloth_set_cloth_contact(Id, other.Id, ref desc));
        }
        /// <summary>Turn contact with other on at this thickness (m) and friction, every other setting default.</summary>
        public void EnableContactWith(Cloth other, float thickness, float friction = 0.0f)
        {
            SetContactWith(other, new ClothClothContactDesc { Enabled = true, Thickness = thickness, Friction = friction });
        }
        /// <summary>Turn contact with other off.</summary>
        public void DisableContactWith(Cloth other)
        {
            SetContactWith(other, new ClothClothContactDesc { Enabled = false });
        }
        public ClothClothContactDesc GetContactWith(Cloth other)
        {
            ClothClothContactDesc s = ClothClothContactDesc.Default();
            ClothException.Check(Native.cloth_get_cloth_contact(Id, other.Id, ref s));
            return s;
        }
        /// <summary>Particles within the thickness of the other cloth in the last frame, and the passes run.</summary>
        public void GetContactCount(Cloth other, out int contacts, out int passes)
        {
            if (other == null) throw new ArgumentNullException("other");
            uint c, p;
            ClothException.Check(Native.cloth_get_cloth_contact_count(Id, other.Id, out c, out p));
            contacts = (int)c;
            passes = (int)p;
        }
        public void SetSpringParams(ClothSpringKind kinds, ClothSpringParams p) { ClothException.Check(Native.cloth_set_spring_params(Id, (uint)kinds, p)); }
        public void SetAero(ClothAeroParams p) { ClothException.Check(Native.cloth_set_aero(Id, ref p)); }
        /// <summary>The wind velocity (m/s, world frame); takes Float3 or a System.Numerics/Unity Vector3.</summary>
        public void SetWind(Float3 wind) { ClothException.Check(Native.cloth_set_wind(Id, ref wind)); }
        public void SetSleep(ClothSleepParams p) { p.EnsureDefaults(); ClothException.Check(Native.cloth_set_sleep(Id, ref p)); }
        public void SetQualityPolicy(ClothQualityPolicy p) { p.EnsureDefaults(); ClothException.Check(Native.cloth_set_quality_policy(Id, ref p)); }
        // The update rate's getter reads two values (rate and phase) and its setter takes an int:
        // written here, not generated.
        /// <summary>Steps every UpdateRate-th world step (1, 2, 4 or 8), reads interpolated between.</summary>
        public int UpdateRate
        {
            get { uint rate, phase; ClothException.Check(Native.cloth_get_update_rate(Id, out rate, out phase)); return (int)rate; }
            set
            {
                if (value < 0) throw new ArgumentOutOfRangeException("value");
                ClothException.Check(Native.cloth_set_update_rate(Id, (uint)value));
            }
        }
        public int UpdatePhase
        {
            get { uint rate, phase; ClothException.Check(Native.cloth_get_update_rate(Id, out rate, out phase)); return (int)phase; }
        }
        /// <summary>Make body the carrier (null removes it; desc is then ignored).</summary>
        public void SetCarrier(Body body, ClothCarrierDesc desc)
        {
            desc.EnsureDefaults();
            ClothException.Check(Native.cloth_set_carrier(Id, body == null ? ClothBodyId.Null : body.Id, ref desc));
        }

        // Snapshots ----------------------------------------------------------------------------------

        public int SnapshotSize
        {
            get { UIntPtr n; ClothException.Check(Native.cloth_get_snapshot_size(Id, out n)); return (int)(ulong)n; }
        }
        /// <summary>A snapshot of the cloth's dynamic state, in a new array.</summary>
        public byte[] SaveSnapshot()
        {
            var bytes = new byte[SnapshotSize];
            SaveSnapshot(bytes);
            return bytes;
        }
        /// <summary>A snapshot into bytes (at least SnapshotSize long), for a caller that reuses its buffer.</summary>
        public void SaveSnapshot(byte[] bytes)
        {
            RequireSome(bytes);
            fixed (byte* p = bytes)
            {
                ClothException.Check(Native.cloth_save_snapshot(Id, (IntPtr)p, (UIntPtr)(ulong)bytes.Length));
            }
        }
    }
}
