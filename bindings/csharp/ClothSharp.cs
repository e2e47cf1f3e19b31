// ClothSharp: the hand-written layer over the generated binding (Native,
// written by generate.py from cloth.h). Owners that destroy what they
// created (World, Fabric, Cloth, Body, Collider), array and Span overloads
// for particle data, and results turned into exceptions. Everything it does
// not wrap is one call away in Native, with each owner's Id.
//
// Errors: a call that fails throws ClothException, which carries the
// cloth_result and the library's message for the call (cloth_get_last_error,
// read on the same thread right after it). World.Step is the exception:
// the results after which the world still advanced (over budget, solver
// stopped at its limit, a cloth restored after going non-finite, the CG
// reference solver out of memory) are returned, not thrown, since a game
// loop meets them every frame it meets them at all.
//
// Compiles as C# 7.2 (Mono 6.8's mcs, Unity 2021.2+, Godot 4 / .NET 6+)
// with unsafe code allowed. Span<T> overloads are left out when
// CLOTH_NO_SPAN is defined (runtimes without System.Span).
using System;
using System.Collections.Concurrent;
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

    /// <summary>Library-wide checks and names.</summary>
    public static class ClothLibrary
    {
        /// <summary>The loaded library's version (not the header's).</summary>
        public static ClothVersion Version { get { return Native.cloth_get_version(); } }

        /// <summary>
        /// Throws unless the loaded library can serve this binding: the same major version, at least
        /// the header's minor version, and every struct of the binding the library's size.
        /// </summary>
        public static void Verify()
        {
            ClothVersion v = Native.cloth_get_version();
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

    /// <summary>Receives the world's error and warning messages (cloth_world_desc.log), on the calling thread.</summary>
    public delegate void ClothLogHandler(ClothLogLevel level, ClothResult code, string message);

    /// <summary>
    /// Profiler zones (cloth_world_set_zone_callbacks). Called on the thread that runs the work, the
    /// world's workers included, concurrently: keep it cheap and thread-safe, and call no cloth API.
    /// </summary>
    public interface IClothZoneListener
    {
        void Begin(string name, uint worker);
        void End(string name, uint worker);
    }

    /// <summary>
    /// A world (cloth_world_id) and everything in it. Dispose destroys it and every object in it; a
    /// world never disposed is destroyed by its finalizer. Threading (cloth.h): one thread at a time
    /// calls a world and the objects in it, and none while Step runs.
    /// </summary>
    public sealed class World : IDisposable
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
            ClothResult r = Native.cloth_world_create(ref desc, out id);
            if (r != ClothResult.Ok)
            {
                string message = Native.cloth_get_last_error_str();
                state.Free();
                throw new ClothException(r, message);
            }
        }

        ~World() { Destroy(); }

        public ClothWorldId Id { get { return id; } }
        public bool IsValid { get { return Native.cloth_world_is_valid(id) != 0; } }

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
        /// Advance every cloth by dt seconds (cloth_step). Returns Ok, or a result after which the
        /// world still advanced: ErrorOverBudget, ErrorSolverFailed, ErrorNonfiniteState (that cloth
        /// was restored; ClothStats.LastStepResult says which) or ErrorOutOfMemory (the CG reference
        /// solver). Throws for everything else (nothing moved).
        /// </summary>
        public ClothResult Step(float dt)
        {
            ClothResult r = Native.cloth_step(id, dt);
            switch (r)
            {
                case ClothResult.Ok:
                case ClothResult.ErrorOverBudget:
                case ClothResult.ErrorSolverFailed:
                case ClothResult.ErrorNonfiniteState:
                case ClothResult.ErrorOutOfMemory:
                    return r;
                default:
                    throw new ClothException(r, Native.cloth_get_last_error_str());
            }
        }

        public Fabric CreateGridFabric(ClothGridDesc desc)
        {
            ClothFabricId f;
            ClothException.Check(Native.cloth_fabric_create_grid(id, ref desc, out f));
            return new Fabric(this, f);
        }

        /// <summary>A mesh fabric: 3 floats per vertex, 3 indices per triangle (copied during the call).</summary>
        public unsafe Fabric CreateMeshFabric(float[] positions, uint[] indices,
                                              uint springKinds = (uint)ClothSpringKind.All)
        {
            if (positions == null) throw new ArgumentNullException("positions");
            if (indices == null) throw new ArgumentNullException("indices");
            ClothMeshDesc desc = ClothMeshDesc.Default();
            desc.VertexCount = (uint)(positions.Length / 3);
            desc.TriangleCount = (uint)(indices.Length / 3);
            desc.SpringKinds = springKinds;
            ClothFabricId f;
            fixed (float* p = positions)
            fixed (uint* i = indices)
            {
                desc.Positions = (IntPtr)p;
                desc.Indices = (IntPtr)i;
                ClothException.Check(Native.cloth_fabric_create_mesh(id, ref desc, out f));
            }
            return new Fabric(this, f);
        }

        /// <summary>A fabric from a Wavefront OBJ file; the path is passed as UTF-8.</summary>
        public Fabric LoadObjFabric(string path, uint springKinds = (uint)ClothSpringKind.All)
        {
            ClothFabricId f;
            ClothException.Check(Native.cloth_fabric_create_obj(id, path, springKinds, out f));
            return new Fabric(this, f);
        }

        /// <summary>A cloth from desc (start from ClothDesc.Default() and set Fabric).</summary>
        public Cloth CreateCloth(ClothDesc desc)
        {
            ClothId c;
            ClothException.Check(Native.cloth_create(id, ref desc, out c));
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
            ClothBodyId b;
            ClothException.Check(Native.cloth_body_create(id, ref desc, out b));
            return new Body(this, b);
        }

        public Collider CreateSphere(ClothColliderDesc desc, float radius)
        {
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_sphere(id, ref desc, radius, out c));
            return new Collider(this, c);
        }

        public Collider CreateCapsule(ClothColliderDesc desc, float radius, float halfHeight)
        {
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_capsule(id, ref desc, radius, halfHeight, out c));
            return new Collider(this, c);
        }

        public Collider CreateTaperedCapsule(ClothColliderDesc desc, float bottomRadius, float topRadius, float halfHeight)
        {
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_tapered_capsule(id, ref desc, bottomRadius, topRadius, halfHeight, out c));
            return new Collider(this, c);
        }

        public Collider CreateBox(ClothColliderDesc desc, Float3 halfExtents)
        {
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_box(id, ref desc, ref halfExtents, out c));
            return new Collider(this, c);
        }

        public Collider CreatePlane(ClothColliderDesc desc, Float3 normal, float offset)
        {
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_plane(id, ref desc, ref normal, offset, out c));
            return new Collider(this, c);
        }

        /// <summary>A convex hull of points (3 floats each).</summary>
        public Collider CreateConvexHull(ClothColliderDesc desc, float[] pointsXyz)
        {
            if (pointsXyz == null || pointsXyz.Length == 0) throw new ArgumentException("no points", "pointsXyz");
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_convex_hull(id, ref desc, ref pointsXyz[0],
                                                                          (uint)(pointsXyz.Length / 3), out c));
            return new Collider(this, c);
        }

        /// <summary>A triangle mesh collider: 3 floats per vertex, 3 indices per triangle.</summary>
        public Collider CreateTriangleMesh(ClothColliderDesc desc, float[] verticesXyz, uint[] indices)
        {
            if (verticesXyz == null || verticesXyz.Length == 0) throw new ArgumentException("no vertices", "verticesXyz");
            if (indices == null || indices.Length == 0) throw new ArgumentException("no indices", "indices");
            ClothColliderId c;
            ClothException.Check(Native.cloth_collider_create_triangle_mesh(
                id, ref desc, ref verticesXyz[0], (uint)(verticesXyz.Length / 3), ref indices[0],
                (uint)(indices.Length / 3), out c));
            return new Collider(this, c);
        }

        /// <summary>A height field of heightfield.Columns x Rows heights (row-major; copied during the call).</summary>
        public unsafe Collider CreateHeightfield(ClothColliderDesc desc, ClothHeightfieldDesc heightfield,
                                                 float[] heights)
        {
            if (heights == null) throw new ArgumentNullException("heights");
            ClothColliderId c;
            fixed (float* h = heights)
            {
                heightfield.Heights = (IntPtr)h;
                ClothException.Check(Native.cloth_collider_create_heightfield(id, ref desc, ref heightfield, out c));
            }
            return new Collider(this, c);
        }

        public void SetGravity(Float3 gravity) { ClothException.Check(Native.cloth_world_set_gravity(id, ref gravity)); }
        public void ShiftOrigin(Float3 shift) { ClothException.Check(Native.cloth_world_shift_origin(id, ref shift)); }
        public void SetWorkerSpin(uint microseconds) { ClothException.Check(Native.cloth_world_set_worker_spin(id, microseconds)); }
        public void SetFrameBudget(float milliseconds) { ClothException.Check(Native.cloth_world_set_frame_budget(id, milliseconds)); }
        /// <summary>The viewer whose distance scales each cloth's importance under a frame budget.</summary>
        public void SetViewer(Float3 position) { ClothException.Check(Native.cloth_world_set_viewer(id, ref position)); }
        public unsafe void ClearViewer() { ClothException.Check(Native.cloth_world_set_viewer(id, (Float3*)null)); }
        public void SetProfiling(uint maxTasksPerFrame) { ClothException.Check(Native.cloth_world_set_profiling(id, maxTasksPerFrame)); }

        /// <summary>
        /// The last step's profile into a struct the caller keeps and reuses: the profile is about
        /// 4 KB of inline arrays (read them with GetStageMs(i), GetWorkerBusyMs(i), ...), so it is
        /// filled in place, never copied per call. Sets profile.StructSize.
        /// </summary>
        public void GetFrameProfile(ref ClothFrameProfile profile)
        {
            profile.StructSize = (uint)Marshal.SizeOf(typeof(ClothFrameProfile));
            ClothException.Check(Native.cloth_world_get_frame_profile(id, ref profile));
        }

        /// <summary>The last frame's task records, at most records.Length; returns how many were copied.</summary>
        public int ReadTaskRecords(ClothTaskRecord[] records)
        {
            if (records == null || records.Length == 0) return 0;
            uint count;
            ClothException.Check(Native.cloth_world_read_task_records(id, out records[0], (uint)records.Length, out count));
            return (int)count;
        }

        /// <summary>The last frame as Chrome trace-event JSON.</summary>
        public unsafe string WriteTraceJson()
        {
            UIntPtr size;
            ClothException.Check(Native.cloth_world_write_trace_json(id, null, UIntPtr.Zero, &size));
            var buffer = new byte[(int)(ulong)size];
            ClothException.Check(Native.cloth_world_write_trace_json(id, ref buffer[0], size, out size));
            return System.Text.Encoding.UTF8.GetString(buffer, 0, buffer.Length - 1);
        }

        /// <summary>Install zone callbacks (null removes them). The listener is called from worker threads.</summary>
        public void SetZoneCallbacks(IClothZoneListener listener)
        {
            var s = (State)state.Target;
            if (listener == null)
            {
                ClothException.Check(Native.cloth_world_set_zone_callbacks(id, IntPtr.Zero, IntPtr.Zero, IntPtr.Zero));
                s.Zones = null;
                return;
            }
            s.Zones = listener;
            ClothException.Check(Native.cloth_world_set_zone_callbacks(id, Callbacks.ZoneBeginPointer,
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
                    if (zones != null) zones.Begin(StaticNames.Get(name), worker);
                }
                catch (Exception) { }
            }

            [MonoPInvokeCallback(typeof(ClothZoneEndFn))]
            static void ZoneEnd(IntPtr name, uint worker, IntPtr user)
            {
                try
                {
                    IClothZoneListener zones = Of(user).Zones;
                    if (zones != null) zones.End(StaticNames.Get(name), worker);
                }
                catch (Exception) { }
            }
        }
    }

    /// <summary>
    /// An object inside a world. Dispose destroys it; after its world is disposed it is already gone
    /// and Dispose does nothing. No finalizer: destroying from the finalizer thread would call a world
    /// while its own thread may be using it (cloth.h's threading contract); the world frees everything
    /// it holds when it is destroyed.
    /// </summary>
    public abstract class WorldObject : IDisposable
    {
        protected WorldObject(World world) { World = world; }
        public World World { get; private set; }
        public bool IsDisposed { get; private set; }

        public void Dispose()
        {
            if (IsDisposed) return;
            IsDisposed = true;
            if (!World.IsValid) return;
            ClothResult r = Destroy();
            // Already gone with what it was fixed to (a collider with its body): nothing to do.
            if (r != ClothResult.Ok && r != ClothResult.ErrorInvalidHandle) ClothException.Check(r);
        }

        protected abstract ClothResult Destroy();
    }

    /// <summary>Shared topology (cloth_fabric_id). Disposing releases the handle; cloths made of it keep working.</summary>
    public sealed class Fabric : WorldObject
    {
        internal Fabric(World world, ClothFabricId id) : base(world) { Id = id; }
        public ClothFabricId Id { get; private set; }
        protected override ClothResult Destroy() { return Native.cloth_fabric_destroy(Id); }

        public int ParticleCount
        {
            get { uint n; ClothException.Check(Native.cloth_fabric_get_particle_count(Id, out n)); return (int)n; }
        }
        public int TriangleCount
        {
            get { uint n; ClothException.Check(Native.cloth_fabric_get_triangle_count(Id, out n)); return (int)n; }
        }
        public int SpringCount(uint kinds)
        {
            uint n;
            ClothException.Check(Native.cloth_fabric_get_spring_count(Id, kinds, out n));
            return (int)n;
        }
        /// <summary>3 indices per triangle into indices (at least 3 * TriangleCount).</summary>
        public void ReadTriangles(uint[] indices)
        {
            if (indices == null || indices.Length == 0) throw new ArgumentException("empty buffer", "indices");
            ClothException.Check(Native.cloth_fabric_read_triangles(Id, out indices[0], (uint)indices.Length));
        }
    }

    /// <summary>A rigid frame the host moves (cloth_body_id). Disposing destroys its colliders and attachments too.</summary>
    public sealed class Body : WorldObject
    {
        internal Body(World world, ClothBodyId id) : base(world) { Id = id; }
        public ClothBodyId Id { get; private set; }
        protected override ClothResult Destroy() { return Native.cloth_body_destroy(Id); }

        /// <summary>The pose reached at the end of the next step (rotation: unit quaternion x, y, z, w).</summary>
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
    }

    /// <summary>A collision shape (cloth_collider_id); it dies with the body it is fixed to.</summary>
    public sealed class Collider : WorldObject
    {
        internal Collider(World world, ClothColliderId id) : base(world) { Id = id; }
        public ClothColliderId Id { get; private set; }
        protected override ClothResult Destroy() { return Native.cloth_collider_destroy(Id); }
        public void SetGroupBits(uint bits) { ClothException.Check(Native.cloth_collider_set_group_bits(Id, bits)); }
    }

    /// <summary>One simulated cloth (cloth_id).</summary>
    public sealed unsafe class Cloth : WorldObject
    {
        internal Cloth(World world, ClothId id) : base(world)
        {
            Id = id;
            uint n;
            ClothException.Check(Native.cloth_get_particle_count(id, out n));
            ParticleCount = (int)n;
        }

        public ClothId Id { get; private set; }
        /// <summary>Particles of the cloth; particle data holds 3 * ParticleCount floats.</summary>
        public int ParticleCount { get; private set; }
        protected override ClothResult Destroy() { return Native.cloth_destroy(Id); }

        // Particle data ------------------------------------------------------------------------------

        public void ReadPositions(float[] xyz) { ReadPositions(xyz, 0); }
        /// <summary>Positions into xyz from offset on (3 floats per particle).</summary>
        public void ReadPositions(float[] xyz, int offset)
        {
            CheckBuffer(xyz, offset);
            fixed (float* p = xyz)
            {
                ClothException.Check(Native.cloth_read_positions(Id, p + offset, (uint)(xyz.Length - offset)));
            }
        }
        /// <summary>Positions into a Float3 per particle (the layout of Unity's and Godot's Vector3).</summary>
        public void ReadPositions(Float3[] vertices)
        {
            CheckBuffer(vertices, 0);
            fixed (Float3* p = vertices)
            {
                ClothException.Check(Native.cloth_read_positions(Id, (float*)p, (uint)(vertices.Length * 3)));
            }
        }
        public void ReadVelocities(float[] xyz)
        {
            CheckBuffer(xyz, 0);
            ClothException.Check(Native.cloth_read_velocities(Id, out xyz[0], (uint)xyz.Length));
        }
        public void ReadNormals(float[] xyz) { ReadNormals(xyz, 0); }
        public void ReadNormals(float[] xyz, int offset)
        {
            CheckBuffer(xyz, offset);
            fixed (float* p = xyz)
            {
                ClothException.Check(Native.cloth_read_normals(Id, p + offset, (uint)(xyz.Length - offset)));
            }
        }
        public void ReadNormals(Float3[] normals)
        {
            CheckBuffer(normals, 0);
            fixed (Float3* p = normals)
            {
                ClothException.Check(Native.cloth_read_normals(Id, (float*)p, (uint)(normals.Length * 3)));
            }
        }

        static void CheckBuffer(Array buffer, int offset)
        {
            if (buffer == null) throw new ArgumentNullException("buffer");
            if (offset < 0 || offset >= buffer.Length) throw new ArgumentOutOfRangeException("offset");
        }

#if !CLOTH_NO_SPAN
        public void ReadPositions(Span<float> xyz)
        {
            fixed (float* p = &MemoryMarshal.GetReference(xyz))
            {
                ClothException.Check(Native.cloth_read_positions(Id, p, (uint)xyz.Length));
            }
        }
        public void ReadVelocities(Span<float> xyz)
        {
            fixed (float* p = &MemoryMarshal.GetReference(xyz))
            {
                ClothException.Check(Native.cloth_read_velocities(Id, p, (uint)xyz.Length));
            }
        }
        public void ReadNormals(Span<float> xyz)
        {
            fixed (float* p = &MemoryMarshal.GetReference(xyz))
            {
                ClothException.Check(Native.cloth_read_normals(Id, p, (uint)xyz.Length));
            }
        }

        /// <summary>Teleport particles to positions (3 floats each); their velocities become zero.</summary>
        public void SetPositions(ReadOnlySpan<uint> indices, ReadOnlySpan<float> xyz)
        {
            RequireTriples(indices, xyz);
            fixed (uint* i = &MemoryMarshal.GetReference(indices))
            fixed (float* p = &MemoryMarshal.GetReference(xyz))
            {
                ClothException.Check(Native.cloth_set_positions(Id, i, p, (uint)indices.Length));
            }
        }
        public void Pin(ReadOnlySpan<uint> indices)
        {
            fixed (uint* i = &MemoryMarshal.GetReference(indices))
            {
                ClothException.Check(Native.cloth_pin(Id, i, (uint)indices.Length));
            }
        }
        public void Unpin(ReadOnlySpan<uint> indices)
        {
            fixed (uint* i = &MemoryMarshal.GetReference(indices))
            {
                ClothException.Check(Native.cloth_unpin(Id, i, (uint)indices.Length));
            }
        }
        /// <summary>Where pinned particles arrive at the end of the next step (3 floats each).</summary>
        public void SetPinTargets(ReadOnlySpan<uint> indices, ReadOnlySpan<float> xyz)
        {
            RequireTriples(indices, xyz);
            fixed (uint* i = &MemoryMarshal.GetReference(indices))
            fixed (float* p = &MemoryMarshal.GetReference(xyz))
            {
                ClothException.Check(Native.cloth_set_pin_targets(Id, i, p, (uint)indices.Length));
            }
        }
        /// <summary>
        /// Attach particles to body at body-local offsets (3 floats each), or, with no offsets, where
        /// they are now relative to the body.
        /// </summary>
        public void Attach(Body body, ReadOnlySpan<uint> indices, ReadOnlySpan<float> localOffsetsXyz)
        {
            if (localOffsetsXyz.Length != 0) RequireTriples(indices, localOffsetsXyz);
            fixed (uint* i = &MemoryMarshal.GetReference(indices))
            fixed (float* o = &MemoryMarshal.GetReference(localOffsetsXyz))
            {
                ClothException.Check(Native.cloth_attach(Id, body.Id, i, localOffsetsXyz.Length == 0 ? null : o,
                                                         (uint)indices.Length));
            }
        }
        public void Detach(ReadOnlySpan<uint> indices)
        {
            fixed (uint* i = &MemoryMarshal.GetReference(indices))
            {
                ClothException.Check(Native.cloth_detach(Id, i, (uint)indices.Length));
            }
        }
        public void SetParticleMasses(ReadOnlySpan<uint> indices, ReadOnlySpan<float> masses)
        {
            if (masses.Length != indices.Length) throw new ArgumentException("one mass per index");
            fixed (uint* i = &MemoryMarshal.GetReference(indices))
            fixed (float* m = &MemoryMarshal.GetReference(masses))
            {
                ClothException.Check(Native.cloth_set_particle_masses(Id, i, m, (uint)indices.Length));
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

        static void RequireTriples(ReadOnlySpan<uint> indices, ReadOnlySpan<float> xyz)
        {
            if (xyz.Length != 3 * indices.Length) throw new ArgumentException("3 floats per index");
        }
#endif

        // The same calls for arrays (and runtimes without Span).
        public void SetPositions(uint[] indices, float[] xyz)
        {
            RequireTriples(indices, xyz);
            ClothException.Check(Native.cloth_set_positions(Id, ref indices[0], ref xyz[0], (uint)indices.Length));
        }
        public void Pin(uint[] indices)
        {
            RequireSome(indices);
            ClothException.Check(Native.cloth_pin(Id, ref indices[0], (uint)indices.Length));
        }
        public void Unpin(uint[] indices)
        {
            RequireSome(indices);
            ClothException.Check(Native.cloth_unpin(Id, ref indices[0], (uint)indices.Length));
        }
        public void SetPinTargets(uint[] indices, float[] xyz)
        {
            RequireTriples(indices, xyz);
            ClothException.Check(Native.cloth_set_pin_targets(Id, ref indices[0], ref xyz[0], (uint)indices.Length));
        }
        /// <summary>Attach particles to body at body-local offsets, or (offsets null) where they are now.</summary>
        public void Attach(Body body, uint[] indices, float[] localOffsetsXyz)
        {
            RequireSome(indices);
            if (localOffsetsXyz == null)
            {
                fixed (uint* i = indices)
                {
                    ClothException.Check(Native.cloth_attach(Id, body.Id, i, null, (uint)indices.Length));
                }
                return;
            }
            RequireTriples(indices, localOffsetsXyz);
            ClothException.Check(Native.cloth_attach(Id, body.Id, ref indices[0], ref localOffsetsXyz[0],
                                                     (uint)indices.Length));
        }
        public void Detach(uint[] indices)
        {
            RequireSome(indices);
            ClothException.Check(Native.cloth_detach(Id, ref indices[0], (uint)indices.Length));
        }
        public void RestoreSnapshot(byte[] snapshot)
        {
            RequireSome(snapshot);
            fixed (byte* p = snapshot)
            {
                ClothException.Check(Native.cloth_restore_snapshot(Id, (IntPtr)p, (UIntPtr)(ulong)snapshot.Length));
            }
        }

        static void RequireSome(Array a)
        {
            if (a == null || a.Length == 0) throw new ArgumentException("an empty or null array");
        }
        static void RequireTriples(uint[] indices, float[] xyz)
        {
            RequireSome(indices);
            if (xyz == null || xyz.Length != 3 * indices.Length) throw new ArgumentException("3 floats per index");
        }

        // Settings and queries -----------------------------------------------------------------------

        public bool IsPinned(uint index)
        {
            byte pinned;
            ClothException.Check(Native.cloth_is_pinned(Id, index, out pinned));
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

        public ClothStats GetStats()
        {
            ClothStats stats = ClothStats.Default();
            ClothException.Check(Native.cloth_get_stats(Id, ref stats));
            return stats;
        }
        public ClothSolverSettings Solver
        {
            get
            {
                ClothSolverSettings s = ClothSolverSettings.Default();
                ClothException.Check(Native.cloth_get_solver(Id, ref s));
                return s;
            }
            set { ClothException.Check(Native.cloth_set_solver(Id, ref value)); }
        }
        public ClothStrainLimit StrainLimit
        {
            get
            {
                ClothStrainLimit s = ClothStrainLimit.Default();
                ClothException.Check(Native.cloth_get_strain_limit(Id, ref s));
                return s;
            }
            set { ClothException.Check(Native.cloth_set_strain_limit(Id, ref value)); }
        }
        public ClothCollisionParams Collision
        {
            get
            {
                ClothCollisionParams s = ClothCollisionParams.Default();
                ClothException.Check(Native.cloth_get_collision(Id, ref s));
                return s;
            }
            set { ClothException.Check(Native.cloth_set_collision(Id, ref value)); }
        }
        public ClothSelfCollisionDesc SelfCollision
        {
            get
            {
                ClothSelfCollisionDesc s = ClothSelfCollisionDesc.Default();
                ClothException.Check(Native.cloth_get_self_collision(Id, ref s));
                return s;
            }
            set { ClothException.Check(Native.cloth_set_self_collision(Id, ref value)); }
        }
        public ClothSelfCollisionStats GetSelfCollisionStats()
        {
            ClothSelfCollisionStats s = ClothSelfCollisionStats.Default();
            ClothException.Check(Native.cloth_get_self_collision_stats(Id, ref s));
            return s;
        }
        /// <summary>Contact with another cloth of the same world (Enabled = 0: off).</summary>
        public void SetContactWith(Cloth other, ClothClothContactDesc desc)
        {
            ClothException.Check(Native.cloth_set_cloth_contact(Id, other.Id, ref desc));
        }
        public ClothClothContactDesc GetContactWith(Cloth other)
        {
            ClothClothContactDesc s = ClothClothContactDesc.Default();
            ClothException.Check(Native.cloth_get_cloth_contact(Id, other.Id, ref s));
            return s;
        }
        /// <summary>Particles within the thickness of the other cloth in the last frame, and the passes run.</summary>
        public void GetContactCount(Cloth other, out uint contacts, out uint passes)
        {
            ClothException.Check(Native.cloth_get_cloth_contact_count(Id, other.Id, out contacts, out passes));
        }
        public void SetSpringParams(uint kinds, ClothSpringParams p) { ClothException.Check(Native.cloth_set_spring_params(Id, kinds, p)); }
        public void SetAero(ClothAeroParams p) { ClothException.Check(Native.cloth_set_aero(Id, ref p)); }
        public void SetWind(Float3 wind) { ClothException.Check(Native.cloth_set_wind(Id, ref wind)); }
        public void SetSleep(ClothSleepParams p) { ClothException.Check(Native.cloth_set_sleep(Id, ref p)); }
        public void SetQualityPolicy(ClothQualityPolicy p) { ClothException.Check(Native.cloth_set_quality_policy(Id, ref p)); }
        /// <summary>How much the cloth matters under a frame budget (>= 0, default 1).</summary>
        public float Importance
        {
            get { float v; ClothException.Check(Native.cloth_get_importance(Id, out v)); return v; }
            set { ClothException.Check(Native.cloth_set_importance(Id, value)); }
        }
        /// <summary>Steps every UpdateRate-th world step (1, 2, 4 or 8), reads interpolated between.</summary>
        public uint UpdateRate
        {
            get { uint rate, phase; ClothException.Check(Native.cloth_get_update_rate(Id, out rate, out phase)); return rate; }
            set { ClothException.Check(Native.cloth_set_update_rate(Id, value)); }
        }
        public uint UpdatePhase
        {
            get { uint rate, phase; ClothException.Check(Native.cloth_get_update_rate(Id, out rate, out phase)); return phase; }
        }
        /// <summary>Make body the carrier (null removes it; desc is then ignored).</summary>
        public void SetCarrier(Body body, ClothCarrierDesc desc)
        {
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
