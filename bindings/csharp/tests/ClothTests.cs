// The C# binding end to end under Mono: every struct's layout against the
// library, a grid cloth stepped and read, stats, a snapshot round trip, a
// body attachment, the frame profile and zone callbacks on worker threads,
// a counting allocator, and the error paths with their messages. Prints one
// line per check and exits non-zero on the first failure.
using System;
using System.Collections.Generic;
using System.Numerics;
using System.Runtime.InteropServices;
using System.Threading;
using ClothSharp;

static class ClothTests
{
    static int checks;

    static void Check(bool condition, string what)
    {
        if (!condition) throw new Exception("FAILED: " + what);
        ++checks;
        Console.WriteLine("ok - " + what);
    }

    static bool Finite(float f) { return !float.IsNaN(f) && !float.IsInfinity(f); }

    static int Main()
    {
        try
        {
            Layouts();
            GridCloth();
            Snapshot();
            Attachment();
            Skin();
            ClothContact();
            Descriptions();
            NumericsTypes();
            CharacterCloth();
            Disposal();
            LevelOfDetail();
            ProfileAndZones();
            Allocator();
            Errors();
            Console.WriteLine("C# binding: all " + checks + " checks passed");
            return 0;
        }
        catch (Exception e)
        {
            Console.WriteLine(e);
            return 1;
        }
    }

    // Every struct of the binding has the library's size (cloth_struct_size), and the library can
    // serve this header.
    static void Layouts()
    {
        ClothVersion v = ClothLibrary.Version;
        Console.WriteLine("library " + v.Major + "." + v.Minor + "." + v.Patch + ", header " + Native.CLOTH_VERSION_MAJOR +
                          "." + Native.CLOTH_VERSION_MINOR + "." + Native.CLOTH_VERSION_PATCH);
        Check(v.Major == Native.CLOTH_VERSION_MAJOR && v.Minor == Native.CLOTH_VERSION_MINOR, "library version is the header's");
        string[] mismatches = Native.CheckStructLayouts();
        foreach (string m in mismatches) Console.WriteLine("  layout mismatch: " + m);
        int kinds = 0;
        foreach (ClothStructKind k in Enum.GetValues(typeof(ClothStructKind)))
        {
            if (k != ClothStructKind.None && k != ClothStructKind.KindForceU32) ++kinds;
        }
        Check(mismatches.Length == 0 && Native.StructTypes.Length == kinds,
              "all " + Native.StructTypes.Length + " structs have the size cloth_struct_size reports");
        ClothLibrary.Verify();
        Check(Marshal.SizeOf(typeof(ClothFrameProfile)) == (int)(ulong)Native.cloth_struct_size(ClothStructKind.FrameProfile),
              "frame profile is " + Marshal.SizeOf(typeof(ClothFrameProfile)) + " bytes on both sides");
        Check(ClothLibrary.ResultName(ClothResult.ErrorCorruptSnapshot) == "CLOTH_ERROR_CORRUPT_SNAPSHOT" &&
              ClothLibrary.StageName(ClothStage.Forces) == "forces",
              "returned strings are copied, not freed (result and stage names, twice)");
        Check(ClothLibrary.ResultName(ClothResult.Ok) == "CLOTH_OK" && ClothLibrary.StageName(ClothStage.Forces) == "forces",
              "the names read again after the first copies");
    }

    static void GridCloth()
    {
        using (var world = new World())
        {
            ClothGridDesc grid = ClothGridDesc.Default();
            grid.Columns = 16;
            grid.Rows = 16;
            using (Fabric fabric = world.CreateGridFabric(grid))
            {
                Check(fabric.ParticleCount == 256 && fabric.TriangleCount == 2 * 15 * 15, "grid fabric: 256 particles, 450 triangles");
                Cloth cloth = world.CreateCloth(fabric);
                Check(cloth.ParticleCount == 256, "cloth of the fabric: 256 particles");
                cloth.Pin(new int[] { 0, 15 });
                Check(cloth.IsPinned(0) && cloth.IsPinned(15) && !cloth.IsPinned(7), "bool outputs: 0 and 15 pinned, 7 not");
                Check(Native.cloth_is_valid(cloth.Id) == 1 && Native.cloth_is_valid(ClothId.Null) == 0, "bool returns: one byte, 1 and 0");
                Check(cloth.Id == cloth.Id && cloth.Id != ClothId.Null && ClothId.Null.IsNull && !cloth.Id.IsNull,
                      "ids compare field by field; the null id is all-zero");

                var xyz = new float[3 * cloth.ParticleCount];
                cloth.ReadPositions(xyz);
                float startY = xyz[3 * 255 + 1];
                ClothStepOutcome last = ClothStepOutcome.Ok;
                for (int frame = 0; frame < 120; ++frame) last = world.Step(1.0f / 60.0f);
                Check(last == ClothStepOutcome.Ok, "120 steps of 1/60 s return Ok");
                var span = new Span<float>(xyz);
                cloth.ReadPositions(span);
                bool finite = true;
                foreach (float f in xyz) finite &= Finite(f);
                Check(finite, "positions finite after 120 steps (Span overload)");
                Check(xyz[0] == 0.0f && xyz[1] == 0.0f && xyz[2] == 0.0f, "pinned corner 0 stayed at the origin");
                var vertices = new Float3[cloth.ParticleCount];
                cloth.ReadPositions(vertices);
                Check(vertices[255].Y == xyz[3 * 255 + 1], "Float3[] overload reads the same positions");
                var normals = new float[3 * 256];
                cloth.ReadNormals(normals);
                float n = normals[0] * normals[0] + normals[1] * normals[1] + normals[2] * normals[2];
                Check(Math.Abs(n - 1.0f) < 1e-3f, "normals are unit length");

                ClothStats stats = cloth.GetStats();
                Console.WriteLine(string.Format("  stats: kinetic {0:F4} J, elastic {1:F4} J, max strain {2:F4}, iterations {3}, substeps {4}",
                                                stats.KineticEnergy, stats.ElasticEnergy, stats.MaxStrain, stats.LastSolverIterations,
                                                stats.LastSubsteps));
                Check(stats.StructSize == (uint)Marshal.SizeOf(typeof(ClothStats)) && stats.LastStepResult == ClothResult.Ok &&
                      stats.MaxStrain > 0.0f && stats.MaxStrain < 0.2f && stats.LastSubsteps > 0,
                      "stats: struct_size kept, last step Ok, strain within 0.2");
                Check(xyz[3 * 255 + 1] < startY, "the free corner fell (y " + startY + " -> " + xyz[3 * 255 + 1] + ")");
                ClothSolverSettings solver = cloth.Solver;
                Check(solver.Kind == ClothSolverKind.Default && solver.StructSize == (uint)Marshal.SizeOf(typeof(ClothSolverSettings)),
                      "solver settings read back (CLOTH_SOLVER_DEFAULT)");
            }
        }
    }

    static bool SameBits(float[] a, float[] b)
    {
        if (a.Length != b.Length) return false;
        for (int i = 0; i < a.Length; ++i)
        {
            if (BitConverter.ToInt32(BitConverter.GetBytes(a[i]), 0) != BitConverter.ToInt32(BitConverter.GetBytes(b[i]), 0)) return false;
        }
        return true;
    }

    static void Snapshot()
    {
        using (var world = new World())
        {
            Fabric fabric = world.CreateGridFabric(ClothGridDesc.Default());
            Cloth cloth = world.CreateCloth(fabric);
            cloth.Pin(new int[] { 0, 31 });
            cloth.SetWind(new Float3(2.0f, 0.0f, 1.0f));
            for (int i = 0; i < 30; ++i) world.Step(1.0f / 60.0f);
            byte[] snapshot = cloth.SaveSnapshot();
            var saved = new float[3 * cloth.ParticleCount];
            cloth.ReadPositions(saved);
            for (int i = 0; i < 30; ++i) world.Step(1.0f / 60.0f);
            var first = new float[saved.Length];
            cloth.ReadPositions(first);

            cloth.RestoreSnapshot(snapshot);
            var restored = new float[saved.Length];
            cloth.ReadPositions(restored);
            Check(SameBits(saved, restored), "snapshot of " + snapshot.Length + " bytes restores the positions bit for bit");
            for (int i = 0; i < 30; ++i) world.Step(1.0f / 60.0f);
            var second = new float[saved.Length];
            cloth.ReadPositions(second);
            Check(SameBits(first, second), "30 steps after the restore repeat the same bits");

            byte[] damaged = (byte[])snapshot.Clone();
            damaged[damaged.Length / 2] ^= 0x01;
            var before = new float[saved.Length];
            cloth.ReadPositions(before);
            try
            {
                cloth.RestoreSnapshot(damaged);
                Check(false, "a flipped byte is refused");
            }
            catch (ClothException e)
            {
                Console.WriteLine("  refused: " + e.Message);
                var after = new float[saved.Length];
                cloth.ReadPositions(after);
                Check(e.Result == ClothResult.ErrorCorruptSnapshot && SameBits(before, after),
                      "a snapshot with one flipped byte is refused (CORRUPT_SNAPSHOT), the cloth unchanged");
            }
            var span = new ReadOnlySpan<byte>(snapshot);
            cloth.RestoreSnapshot(span);
            cloth.ReadPositions(restored);
            Check(SameBits(saved, restored), "the intact snapshot restores again (ReadOnlySpan<byte> overload)");
        }
    }

    // Character cloth through the binding: a skin description whose arrays
    // are pointer fields, joint matrices, max distances (0 pins a particle
    // to its skinned position), the skinned positions read back.
    // Two cloths of one world in contact: a sheet dropped 3 cm above another, shifted half a cell.
    static unsafe void ClothContact()
    {
        using (var world = new World())
        {
            ClothGridDesc grid = ClothGridDesc.Default();
            grid.Columns = 16;
            grid.Rows = 16;
            Fabric fabric = world.CreateGridFabric(grid);
            Cloth lower = world.CreateCloth(fabric);
            var start = new float[3 * 256];
            lower.ReadPositions(start);
            for (int v = 0; v < 256; ++v)
            {
                start[3 * v] += 0.03f;
                start[3 * v + 2] += 0.03f;
            }
            Cloth upper;
            fixed (float* x = start)
            {
                ClothDesc desc = ClothDesc.Default();
                desc.Fabric = fabric.Id;
                desc.InitialPositions = (IntPtr)x;
                upper = world.CreateCloth(desc);
            }
            int[] corners = { 0, 15, 240, 255 };
            lower.Pin(corners);
            upper.Pin(corners);
            ClothClothContactDesc contact = ClothClothContactDesc.Default();
            Check(!contact.Enabled && !upper.GetContactWith(lower).Enabled, "cloths are not in contact by default");
            lower.EnableContactWith(upper, 0.05f);
            ClothClothContactDesc back = upper.GetContactWith(lower);
            Check(back.Enabled && back.Thickness == 0.05f && back.Passes == contact.Passes,
                  "EnableContactWith turns the pair on (bool flag), other settings default; it reads back from either cloth");
            contact.Enabled = true;
            contact.Thickness = 0.05f;
            int contacts = 0, passes = 0, seen = 0;
            for (int frame = 0; frame < 30; ++frame)
            {
                world.Step(1.0f / 60.0f);
                upper.GetContactCount(lower, out contacts, out passes);
                seen += contacts;
            }
            Check(seen > 0, "the sheets touched (" + seen + " particle contacts over 30 frames)");
            try
            {
                lower.SetContactWith(lower, contact);
                Check(false, "a cloth and itself is refused");
            }
            catch (ClothException e)
            {
                Check(e.Result == ClothResult.ErrorInvalidValue, "a cloth and itself is refused (INVALID_VALUE)");
            }
        }
    }

    // Descriptions cannot be built wrong: `new X { ... }` keeps the library's defaults for what it does
    // not set, and an all-zero one given to an owner takes every default.
    static void Descriptions()
    {
        ClothGridDesc defaults = ClothGridDesc.Default();
        var grid = new ClothGridDesc { Columns = 8, Rows = 4 };
        Check(grid.IsInitialized && grid.StructSize == defaults.StructSize && grid.U.X == defaults.U.X &&
              grid.SpringKinds == defaults.SpringKinds && grid.Columns == 8,
              "new ClothGridDesc { Columns = 8, Rows = 4 } holds the library's defaults for the rest");
        Check(default(ClothGridDesc).Columns == defaults.Columns && !default(ClothGridDesc).IsInitialized,
              "an all-zero description reads as the defaults (" + defaults.Columns + " columns)");
        using (var world = new World(new ClothWorldDesc { WorkerCount = 1 }))
        {
            Check(world.CreateGridFabric(grid).ParticleCount == 32, "a grid from new ClothGridDesc { ... }: 8 x 4 particles");
            Check(world.CreateGridFabric(new ClothGridDesc()).ParticleCount == (int)(defaults.Columns * defaults.Rows),
                  "new ClothGridDesc() given to the owner takes every default");
            Fabric fabric = world.CreateGridFabric(grid);
            Cloth cloth = world.CreateCloth(new ClothDesc { Fabric = fabric.Id });
            Check(cloth.ParticleCount == 32 && cloth.Solver.Kind == ClothDesc.Default().Solver.Kind,
                  "new ClothDesc { Fabric = ... } makes a cloth with the default solver");
            var collision = new ClothCollisionParams { Friction = 0.25f };
            cloth.Collision = collision;
            Check(cloth.Collision.Friction == 0.25f, "new ClothCollisionParams { Friction = 0.25f } is accepted and reads back");
            // The other generated get/set properties (ClothSharp.g.cs) round-trip too.
            cloth.StrainLimit = new ClothStrainLimit { MaxStrain = 0.05f };
            Check(cloth.StrainLimit.MaxStrain == 0.05f, "new ClothStrainLimit { MaxStrain = 0.05f } is accepted and reads back");
            cloth.SelfCollision = new ClothSelfCollisionDesc { Enabled = true, Thickness = 0.02f };
            Check(cloth.SelfCollision.Enabled && cloth.SelfCollision.Thickness == 0.02f,
                  "new ClothSelfCollisionDesc { Enabled = true, Thickness = 0.02f } is accepted and reads back");
            var solver = cloth.Solver;
            solver.Iterations = 3;
            cloth.Solver = solver;
            Check(cloth.Solver.Iterations == 3, "a solver setting changed on a copy is set and reads back");
        }
    }

    // System.Numerics: Vector3 and Quaternion wherever the API takes or returns points and rotations.
    static void NumericsTypes()
    {
        using (var world = new World())
        {
            Cloth cloth = world.CreateCloth(world.CreateGridFabric(new ClothGridDesc { Columns = 8, Rows = 8 }));
            cloth.Pin(new int[] { 0, 7 });
            cloth.SetWind(new Vector3(3.0f, 0.0f, 1.0f));
            world.SetGravity(new Vector3(0.0f, -9.81f, 0.0f));
            for (int frame = 0; frame < 10; ++frame) world.Step(1.0f / 60.0f);
            var v = new Vector3[cloth.ParticleCount];
            var f = new float[3 * cloth.ParticleCount];
            cloth.ReadPositions(v);
            cloth.ReadPositions(f);
            Span<Vector3> span = new Vector3[cloth.ParticleCount];
            cloth.ReadPositions(span);
            Check(v[63].X == f[189] && v[63].Y == f[190] && v[63].Z == f[191] && span[63] == v[63] && v[63].Y < 0.0f,
                  "ReadPositions(Vector3[]) and (Span<Vector3>) read what the float[] overload reads: " + v[63]);
            var n = new Vector3[cloth.ParticleCount];
            cloth.ReadNormals(n);
            Check(Math.Abs(n[20].Length() - 1.0f) < 1e-3f, "ReadNormals(Vector3[]): unit normals");
            cloth.SetPositions(new int[] { 63 }, new Vector3[] { new Vector3(5.0f, 6.0f, 7.0f) });
            cloth.ReadPositions(v);
            Check(v[63] == new Vector3(5.0f, 6.0f, 7.0f), "SetPositions(int[], Vector3[]) teleports a particle");

            Quaternion turn = Quaternion.CreateFromAxisAngle(Vector3.UnitY, 0.5f);
            Body body = world.CreateBody(new Vector3(1.0f, 2.0f, 3.0f), Quaternion.Identity);
            body.SetPose(new Vector3(4.0f, 5.0f, 6.0f), turn);
            Vector3 p;
            Quaternion q;
            body.GetPose(out p, out q);
            Check(p == new Vector3(4.0f, 5.0f, 6.0f) && q == turn && body.Rotation == turn,
                  "Body.SetPose/GetPose with Vector3 and Quaternion: " + p + " " + q);
            cloth.Attach(body, new int[] { 0 }, new Vector3[] { new Vector3(0.0f, 0.0f, 0.5f) });
            Vector3 offset;
            Check(cloth.GetAttachment(0, out offset) == body && offset.Z == 0.5f && cloth.GetAttachment(5, out offset) == null,
                  "Attach(Body, int[], Vector3[]) and GetAttachment return the Body owner and the offset");
            world.SetBodyPoses(new Body[] { body }, new Vector3[] { new Vector3(-1.0f, 0.0f, 0.0f) },
                               new Quaternion[] { Quaternion.Identity });
            body.GetPose(out p, out q);
            Check(p.X == -1.0f && q == Quaternion.Identity, "World.SetBodyPoses with Vector3[] and Quaternion[]");
        }
    }

    // Character cloth in the high layer: skin with int joints, System.Numerics joint matrices, max
    // distances and backstops from managed arrays, no unsafe code.
    static void CharacterCloth()
    {
        using (var world = new World())
        {
            Cloth cape = world.CreateCloth(world.CreateGridFabric(new ClothGridDesc { Columns = 8, Rows = 8 }));
            var rest = new Vector3[64];
            cape.ReadPositions(rest);
            var joints = new int[64];
            for (int v = 0; v < 64; ++v) joints[v] = v < 32 ? 0 : 1;
            cape.SetSkin(2, 1, joints, null);
            var reach = new float[64];  // all 0: every particle pinned to its skinned position
            cape.SetMaxDistances(reach);
            var distances = new float[64];
            var radii = new float[64];
            for (int v = 0; v < 64; ++v) { distances[v] = 0.2f; radii[v] = 0.1f; }
            cape.SetBackstops(distances, radii);
            // Joint 0 lifted 1 m, joint 1 turned a quarter about y: System.Numerics' row-vector matrices.
            cape.SetJointMatrices(new Matrix4x4[] { Matrix4x4.CreateTranslation(0.0f, 1.0f, 0.0f),
                                                    Matrix4x4.CreateRotationY((float)(Math.PI / 2)) });
            world.Step(1.0f / 60.0f);
            var x = new Vector3[64];
            var skinned = new Vector3[64];
            var normals = new Vector3[64];
            cape.ReadPositions(x);
            cape.ReadSkinnedPositions(skinned, normals);
            Vector3 turned = Vector3.Transform(rest[40], Matrix4x4.CreateRotationY((float)(Math.PI / 2)));
            Check(Vector3.Distance(x[3], rest[3] + new Vector3(0.0f, 1.0f, 0.0f)) < 1e-5f &&
                  Vector3.Distance(x[40], turned) < 1e-5f && Vector3.Distance(skinned[40], x[40]) < 1e-5f,
                  "SetJointMatrices(Matrix4x4[]): particle 3 lifted 1 m, particle 40 turned a quarter " + x[40] + " = " + turned);
            Check(cape.IsPinned(10), "SetMaxDistances(float[]) of 0 pins to the skin");

            // Contact between two garments from managed code: a second cloth, EnableContactWith.
            Cloth skirt = world.CreateCloth(world.CreateGridFabric(new ClothGridDesc { Columns = 8, Rows = 8 }));
            cape.EnableContactWith(skirt, 0.01f, 0.2f);
            ClothClothContactDesc pair = skirt.GetContactWith(cape);
            Check(pair.Enabled && pair.Friction == 0.2f, "EnableContactWith sets the pair from managed code");
            cape.DisableContactWith(skirt);
            Check(!skirt.GetContactWith(cape).Enabled, "DisableContactWith turns it off");
            try
            {
                cape.SetSkin(2, 1, new int[3], null);
                Check(false, "a skin of the wrong length is refused");
            }
            catch (ArgumentException)
            {
                Check(true, "a skin of the wrong length throws ArgumentException before any native call");
            }
        }
    }

    // ObjectDisposedException after Dispose, and objects of a disposed world are disposed too.
    static void Disposal()
    {
        var world = new World();
        Fabric fabric = world.CreateGridFabric(new ClothGridDesc { Columns = 4, Rows = 4 });
        Cloth cloth = world.CreateCloth(fabric);
        Body body = world.CreateBody(ClothBodyDesc.Default());
        Check(!cloth.IsDisposed && !world.IsDisposed, "live objects are not disposed");
        world.Dispose();
        Check(world.IsDisposed && cloth.IsDisposed && fabric.IsDisposed && body.IsDisposed,
              "disposing the world makes its cloths, fabrics and bodies IsDisposed");
        int thrown = 0;
        Action[] calls =
        {
            () => cloth.ReadPositions(new float[48]),
            () => cloth.Pin(new int[] { 0 }),
            () => { var unused = cloth.Id; },
            () => body.SetPose(new Vector3(0, 0, 0), Quaternion.Identity),
            () => { var unused = fabric.ParticleCount; },
            () => world.Step(1.0f / 60.0f),
            () => world.CreateGridFabric(ClothGridDesc.Default()),
        };
        foreach (Action call in calls)
        {
            try { call(); }
            catch (ObjectDisposedException) { ++thrown; }
        }
        Check(thrown == calls.Length, "every call on a disposed world or its objects throws ObjectDisposedException (" +
                                      thrown + " of " + calls.Length + ")");
        cloth.Dispose();  // after the world: nothing to do, no exception
        Check(cloth.IsDisposed, "disposing a cloth after its world does nothing");
    }

    static void LevelOfDetail()
    {
        using (var world = new World())
        {
            ClothGridDesc grid = ClothGridDesc.Default();
            grid.Columns = 8;
            grid.Rows = 8;
            Fabric fabric = world.CreateGridFabric(grid);
            Cloth a = world.CreateCloth(fabric), b = world.CreateCloth(fabric);
            Check(a.Importance == 1.0f && a.UpdateRate == 1, "importance 1 and rate 1 by default");
            a.Importance = 0.25f;
            a.UpdateRate = 2;
            b.UpdateRate = 2;
            Check(a.Importance == 0.25f && a.UpdateRate == 2, "importance and rate read back");
            Check(a.UpdatePhase != b.UpdatePhase, "two cloths of one rate are staggered");
            world.SetViewer(new Float3(0.0f, 1.0f, 5.0f));
            for (int frame = 0; frame < 5; ++frame) world.Step(1.0f / 60.0f);
            world.ClearViewer();
            b.Sleep();
            world.Step(1.0f / 60.0f);
            Check(b.IsSleeping, "a cloth the host put to sleep stays asleep");
            b.Wake();
            Check(!b.IsSleeping, "and wakes on the host's word");
            try
            {
                a.UpdateRate = 3;
                Check(false, "rate 3 is refused");
            }
            catch (ClothException e)
            {
                Check(e.Result == ClothResult.ErrorInvalidValue && a.UpdateRate == 2,
                      "rate 3 is refused (INVALID_VALUE) and the rate stays");
            }
        }
    }

    static unsafe void Skin()
    {
        using (var world = new World())
        {
            ClothGridDesc grid = ClothGridDesc.Default();
            grid.Columns = 8;
            grid.Rows = 8;
            Fabric fabric = world.CreateGridFabric(grid);
            Cloth cloth = world.CreateCloth(fabric);
            var joints = new uint[64];
            var reach = new float[64];
            for (int v = 0; v < 64; ++v)
            {
                joints[v] = v < 8 ? 0u : 1u;
                reach[v] = v < 8 ? 0.0f : 0.05f;
            }
            ClothSkinDesc skin = ClothSkinDesc.Default();
            skin.ParticleCount = 64;
            skin.JointCount = 2;
            skin.Influences = 1;
            fixed (uint* j = joints)
            {
                skin.Joints = (IntPtr)j;
                ClothException.Check(Native.cloth_set_skin(cloth.Id, ref skin));
            }
            ClothException.Check(Native.cloth_set_max_distances(cloth.Id, ref reach[0], 64));
            Check(cloth.IsPinned(3) && !cloth.IsPinned(8), "a max distance of 0 pins the top row");
            // Both joints 1 m along x: column-major 4x4 matrices.
            var m = new float[32];
            for (int k = 0; k < 2; ++k)
            {
                m[16 * k] = m[16 * k + 5] = m[16 * k + 10] = m[16 * k + 15] = 1.0f;
                m[16 * k + 12] = 1.0f;
            }
            ClothException.Check(Native.cloth_set_joint_matrices(cloth.Id, ref m[0], 2, ClothMatrixLayout.ColumnMajor4x4));
            for (int frame = 0; frame < 10; ++frame) world.Step(1.0f / 60.0f);
            var s = new float[192];
            var n = new float[192];
            var x = new float[192];
            ClothException.Check(Native.cloth_read_skinned_positions(cloth.Id, out s[0], out n[0], 192));
            cloth.ReadPositions(x);
            float worst = 0.0f;
            for (int v = 8; v < 64; ++v)
            {
                float dx = x[3 * v] - s[3 * v], dy = x[3 * v + 1] - s[3 * v + 1], dz = x[3 * v + 2] - s[3 * v + 2];
                worst = Math.Max(worst, (float)Math.Sqrt(dx * dx + dy * dy + dz * dz) - reach[v]);
            }
            Check(Math.Abs(s[3 * 3] - (3.0f / 7.0f + 1.0f)) < 1e-5f && Math.Abs(x[3 * 3] - s[3 * 3]) < 1e-5f,
                  "the skin moved 1 m with its joints and the pinned row with it");
            Check(worst <= 1e-5f, "every other particle within its max distance of the skin (" + worst + " m past)");
        }
    }

    static void Attachment()
    {
        using (var world = new World())
        {
            ClothGridDesc grid = ClothGridDesc.Default();
            grid.Columns = 8;
            grid.Rows = 8;
            Fabric fabric = world.CreateGridFabric(grid);
            Cloth cloth = world.CreateCloth(fabric);
            Body pole = world.CreateBody(ClothBodyDesc.Default());
            // The top row hangs from the pole, 0.1 m in front of its axis.
            var top = new int[8];
            var offsets = new float[3 * 8];
            for (int c = 0; c < 8; ++c)
            {
                top[c] = c;
                offsets[3 * c + 0] = c / 7.0f;
                offsets[3 * c + 2] = 0.1f;
            }
            cloth.Attach(pole, top, offsets);
            Check(cloth.IsPinned(3), "attached particles report pinned");
            Collider sphere = world.CreateSphere(ClothColliderDesc.Default(), 0.2f);
            float x = 0.0f;
            for (int frame = 0; frame < 60; ++frame)
            {
                x += 0.05f;  // 3 m/s along x
                pole.SetPose(new Float3(x, 1.0f, 0.0f), new Float4(0, 0, 0, 1));
                pole.SetVelocity(new Float3(3.0f, 0.0f, 0.0f), new Float3(0, 0, 0));
                world.Step(1.0f / 60.0f);
            }
            var xyz = new float[3 * cloth.ParticleCount];
            cloth.ReadPositions(xyz);
            float error = 0.0f;
            for (int c = 0; c < 8; ++c)
            {
                error = Math.Max(error, Math.Abs(xyz[3 * c] - (x + c / 7.0f)));
                error = Math.Max(error, Math.Abs(xyz[3 * c + 1] - 1.0f));
                error = Math.Max(error, Math.Abs(xyz[3 * c + 2] - 0.1f));
            }
            Check(error < 1e-5f, "the attached row sits at body pose * offset after 60 frames (error " + error + " m)");
            Float3 p;
            Float4 q;
            pole.GetPose(out p, out q);
            Check(Math.Abs(p.X - x) < 1e-6f && q.W == 1.0f, "body pose reads back " + p);
            Check(xyz[3 * 60] > 2.0f && Finite(xyz[3 * 60 + 1]), "the free rows were carried along (bottom row x 0.571 -> " + xyz[3 * 60] + " m)");
            pole.Dispose();
            Check(!cloth.IsPinned(3) && Native.cloth_collider_is_valid(sphere.Id) == 1,
                  "disposing the body frees its attachments; the static collider stays");
            ClothColliderId sphereId = sphere.Id;
            sphere.Dispose();  // a static collider: destroyed now
            Check(Native.cloth_collider_is_valid(sphereId) == 0 && sphere.IsDisposed, "collider disposed");
        }
    }

    // Counts zones per thread; called by the library's workers concurrently.
    sealed class ZoneCounter : IClothZoneListener
    {
        public int Begins, Ends, MaxWorker;
        public readonly Dictionary<int, int> Threads = new Dictionary<int, int>();
        public readonly HashSet<string> Names = new HashSet<string>();

        public void Begin(string name, int worker)
        {
            Interlocked.Increment(ref Begins);
            lock (Threads)
            {
                int id = Thread.CurrentThread.ManagedThreadId;
                int n;
                Threads.TryGetValue(id, out n);
                Threads[id] = n + 1;
                Names.Add(name);
                if (worker > MaxWorker) MaxWorker = worker;
            }
        }

        public void End(string name, int worker) { Interlocked.Increment(ref Ends); }
    }

    static void ProfileAndZones()
    {
        ClothWorldDesc desc = ClothWorldDesc.Default();
        desc.WorkerCount = 4;
        using (var world = new World(desc))
        {
            ClothGridDesc grid = ClothGridDesc.Default();
            grid.Columns = 64;
            grid.Rows = 64;
            Fabric fabric = world.CreateGridFabric(grid);
            Cloth cloth = world.CreateCloth(fabric);
            cloth.Pin(new int[] { 0, 63 });
            var zones = new ZoneCounter();
            world.SetZoneCallbacks(zones);
            world.SetProfiling(4096);
            world.SetWorkerSpin(2000);  // workers keep polling between these back-to-back steps
            for (int i = 0; i < 20; ++i) world.Step(1.0f / 60.0f);
            world.SetZoneCallbacks(null);
            world.Step(1.0f / 60.0f);
            var profile = ClothFrameProfile.Default();
            world.GetFrameProfile(ref profile);
            double stages = 0.0;
            for (int s = 0; s < Native.CLOTH_MAX_STAGES; ++s) stages += profile.GetStageMs(s);
            double busy = 0.0;
            for (int w = 0; w < profile.WorkerCount; ++w) busy += profile.GetWorkerBusyMs(w);
            Console.WriteLine(string.Format("  profile: frame {0}, step {1:F3} ms, {2} workers, busy {3:F3} ms, {4} tasks, solve {5:F3} ms",
                                            profile.Frame, profile.StepMs, profile.WorkerCount, busy, profile.TaskCount,
                                            profile.GetStageMs((int)ClothStage.IterativeSolve)));
            Check(profile.Frame == 21 && profile.WorkerCount == 4 && profile.StepMs > 0.0 && stages > 0.0 && busy > 0.0 &&
                  profile.TaskCount > 0 && profile.GetStageTasks((int)ClothStage.Forces) > 0,
                  "frame profile: frame 21, 4 workers, stage and worker times, task records");
            var records = new ClothTaskRecord[profile.TaskCount];
            int count = world.ReadTaskRecords(records);
            Check(count == (int)profile.TaskCount && records[0].Cloth == cloth.Id && records[count - 1].EndUs >= records[0].StartUs,
                  count + " task records name the cloth");
            string trace = world.WriteTraceJson();
            Check(trace.StartsWith("{") && trace.Contains("\"forces\""), "trace JSON of " + trace.Length + " characters");

            Console.WriteLine("  zones: " + zones.Begins + " on " + zones.Threads.Count + " threads, highest worker " + zones.MaxWorker +
                              ", names " + string.Join(" ", new List<string>(zones.Names).ToArray()));
            Check(zones.Begins == zones.Ends && zones.Begins > 20, "every zone that began ended (" + zones.Begins + ")");
            Check(zones.Names.Contains("cloth_step") && zones.Names.Contains("forces"), "zones name the step and its stages");
            Check(zones.Threads.Count >= 2 && zones.MaxWorker >= 1, "zone callbacks ran on worker threads (" + zones.Threads.Count + " threads)");
        }
    }

    // Memory from the managed side: alignment up to 64, and free receives the aligned pointer with
    // its size, so each block is over-allocated and the raw pointer kept in a map.
    sealed class CountingAllocator : ClothAllocator
    {
        public int Allocations, Frees, BadFrees;
        public ulong LiveBytes, MaxAlignment;
        readonly Dictionary<long, KeyValuePair<IntPtr, ulong>> blocks = new Dictionary<long, KeyValuePair<IntPtr, ulong>>();

        public override IntPtr Allocate(ulong size, ulong alignment)
        {
            if (alignment == 0 || (alignment & (alignment - 1)) != 0 || alignment > 64) return IntPtr.Zero;
            IntPtr raw = Marshal.AllocHGlobal((IntPtr)(long)(size + alignment));
            long aligned = ((long)raw + (long)alignment - 1) & ~((long)alignment - 1);
            lock (blocks) blocks.Add(aligned, new KeyValuePair<IntPtr, ulong>(raw, size));
            ++Allocations;
            LiveBytes += size;
            if (alignment > MaxAlignment) MaxAlignment = alignment;
            return (IntPtr)aligned;
        }

        public override void Free(IntPtr pointer, ulong size)
        {
            KeyValuePair<IntPtr, ulong> block;
            lock (blocks)
            {
                if (!blocks.TryGetValue((long)pointer, out block) || block.Value != size)
                {
                    ++BadFrees;
                    return;
                }
                blocks.Remove((long)pointer);
            }
            ++Frees;
            LiveBytes -= size;
            Marshal.FreeHGlobal(block.Key);
        }

        public int Live { get { lock (blocks) return blocks.Count; } }
    }

    static void Allocator()
    {
        var allocator = new CountingAllocator();
        var world = new World(ClothWorldDesc.Default(), allocator);
        int afterWorld = allocator.Allocations;
        Fabric fabric = world.CreateGridFabric(ClothGridDesc.Default());
        Cloth cloth = world.CreateCloth(fabric);
        int afterCloth = allocator.Allocations;
        world.Step(1.0f / 60.0f);
        int afterStep = allocator.Allocations;
        world.SetProfiling(1024);  // allocated from the world's allocator
        cloth.Dispose();
        fabric.Dispose();
        Check(afterWorld > 0 && afterCloth > afterWorld && allocator.Allocations > afterStep,
              "world, cloth and profiling memory came from the C# allocator (" + allocator.Allocations + " blocks)");
        Check(afterStep == afterCloth, "a step allocates nothing");
        world.Dispose();
        Console.WriteLine("  allocator: " + allocator.Allocations + " allocations, " + allocator.Frees + " frees, largest alignment " +
                          allocator.MaxAlignment);
        Check(allocator.Frees == allocator.Allocations && allocator.Live == 0 && allocator.LiveBytes == 0 && allocator.BadFrees == 0,
              "every block freed once, with its aligned pointer and size");
        IntPtr block = allocator.Allocate(1000, 64);
        bool aligned = ((long)block & 63) == 0;
        allocator.Free(block, 1000);
        Check(allocator.MaxAlignment == 64 && aligned && allocator.Live == 0 && allocator.BadFrees == 0,
              "the allocator serves alignment 64 too (the library asked for up to 16 here; cloth.h allows 64)");
    }

    static void Errors()
    {
        var messages = new List<string>();
        using (var world = new World(ClothWorldDesc.Default(), null, (level, code, message) => messages.Add(code + ": " + message)))
        {
            try
            {
                world.Step(0.0f);
                Check(false, "dt 0 is refused");
            }
            catch (ClothException e)
            {
                Console.WriteLine("  " + e.Message);
                Check(e.Result == ClothResult.ErrorInvalidValue && e.Message.Contains("cloth_step"),
                      "dt 0 throws ClothException(INVALID_VALUE) with the library's message");
                Check(messages.Count == 0, "an error that is thrown is not logged as well (one channel per error)");
            }

            // A budget no step meets: the world advances, Step returns OverBudget (no exception) and the
            // log handler hears the warning.
            Cloth budgeted = world.CreateCloth(world.CreateGridFabric(new ClothGridDesc { Columns = 8, Rows = 8 }));
            world.SetFrameBudget(1e-6f);
            var before = new Vector3[budgeted.ParticleCount];
            var after = new Vector3[budgeted.ParticleCount];
            budgeted.ReadPositions(before);
            ClothStepOutcome outcome = world.Step(1.0f / 60.0f);
            budgeted.ReadPositions(after);
            Check(outcome == ClothStepOutcome.OverBudget && after[63].Y < before[63].Y,
                  "over budget: the world advanced and Step returned OverBudget (" + outcome + ")");
            Check(messages.Count == 1 && messages[0].StartsWith(ClothResult.ErrorOverBudget + ":"),
                  "the log handler heard the step outcome's warning: " + (messages.Count > 0 ? messages[0] : "nothing"));
            world.SetFrameBudget(0.0f);
            budgeted.Dispose();

            try
            {
                budgeted.Pin(new int[] { 0 });
                Check(false, "a disposed cloth is refused");
            }
            catch (ObjectDisposedException)
            {
                Check(budgeted.IsDisposed, "a disposed cloth throws ObjectDisposedException");
            }

            // Only the raw layer can still pass an all-zero description, and the library refuses it.
            var zero = new ClothGridDesc();
            ClothFabricId none;
            Check(!zero.IsInitialized &&
                  Native.cloth_fabric_create_grid(world.Id, ref zero, out none) == ClothResult.ErrorInvalidDesc,
                  "an all-zero description through Native is refused (INVALID_DESC)");

            world.CreateTaperedCapsule(ClothColliderDesc.Default(), 0.1f, 0.05f, 0.3f);
            try
            {
                world.CreateTaperedCapsule(ClothColliderDesc.Default(), 0.5f, 0.1f, 0.1f);
                Check(false, "a tapered capsule whose bottom sphere holds its top one is refused");
            }
            catch (ClothException e)
            {
                Check(e.Result == ClothResult.ErrorInvalidValue && e.Message.Contains("sphere"),
                      "a tapered capsule whose bottom sphere holds its top one is refused (INVALID_VALUE: use a sphere)");
            }

            string path = "/nonexistent/\u00e9toffe-\u5e03.obj";
            try
            {
                world.LoadObjFabric(path);
                Check(false, "a missing OBJ file is refused");
            }
            catch (ClothException e)
            {
                Console.WriteLine("  " + e.Message);
                Check(e.Result == ClothResult.ErrorIo && e.LibraryMessage.Contains(path), "the OBJ path goes in and comes back as UTF-8");
            }

            // A message cut to the library's buffer ends on a whole UTF-8 character.
            string longPath = "/nonexistent/" + new string('\u00e9', 400) + ".obj";
            try
            {
                world.LoadObjFabric(longPath);
            }
            catch (ClothException e)
            {
                Check(e.Result == ClothResult.ErrorIo && e.LibraryMessage.IndexOf('\uFFFD') < 0 && e.LibraryMessage.Length < longPath.Length,
                      "a truncated message is still valid UTF-8 (" + e.LibraryMessage.Length + " characters)");
            }

            var stale = world.CreateGridFabric(ClothGridDesc.Default());
            ClothFabricId id = stale.Id;
            stale.Dispose();
            uint n;
            ClothResult r = Native.cloth_fabric_get_particle_count(id, out n);
            Check(r == ClothResult.ErrorInvalidHandle && ClothLibrary.LastError.Length > 0,
                  "a destroyed fabric's id is refused: " + ClothLibrary.LastError);
        }
    }
}
