// A user's program built against nothing but the unpacked Unity package
// (Runtime/*.cs compiled as its .asmdef says, Runtime/Plugins/x86_64/
// libcloth.so copied next to the program): compiled without -unsafe, it
// drapes a pinned cloth, a second cloth in contact with it and a skinned
// row, and checks the numbers. Exits non-zero on a failed check.
using System;
using System.Numerics;
using ClothSharp;

static class UnityPackageConsumer
{
    static int failures;

    static void Check(bool condition, string what)
    {
        Console.WriteLine((condition ? "ok - " : "FAILED: ") + what);
        if (!condition) ++failures;
    }

    static int Main()
    {
        ClothLibrary.Verify();
        ClothVersion v = ClothLibrary.Version;
        Check(v.Major == Native.CLOTH_VERSION_MAJOR && v.Minor == Native.CLOTH_VERSION_MINOR,
              "the package's plugin is the version of its generated binding (" + v.Major + "." + v.Minor + "." + v.Patch + ")");
        using (var world = new World(new ClothWorldDesc { WorkerCount = 2 }))
        {
            Fabric fabric = world.CreateGridFabric(new ClothGridDesc { Columns = 16, Rows = 16 });
            Cloth sheet = world.CreateCloth(fabric);
            sheet.Pin(new[] { 0, 15 });
            sheet.SetWind(new Vector3(0.0f, 0.0f, 2.0f));
            var start = new Vector3[sheet.ParticleCount];
            sheet.ReadPositions(start);
            ClothStepOutcome outcome = ClothStepOutcome.Ok;
            for (int frame = 0; frame < 60; ++frame) outcome = world.Step(1.0f / 60.0f);
            var x = new Vector3[sheet.ParticleCount];
            sheet.ReadPositions(x);
            bool finite = true;
            foreach (Vector3 p in x) finite &= !float.IsNaN(p.X + p.Y + p.Z) && !float.IsInfinity(p.X + p.Y + p.Z);
            Check(outcome == ClothStepOutcome.Ok && finite, "60 steps: Ok, every position finite");
            Check(x[0] == start[0] && x[15] == start[15], "the pinned corners stayed where they were");
            // The default grid hangs from its top row (v points down); the wind along +z swings it out.
            Check(x[255].Z > start[255].Z + 0.1f && x[255].Y < x[0].Y,
                  "the wind swung the free corner along +z, below the pinned row: " + start[255] + " -> " + x[255]);
            // The same scene through cloth.h (package_scene.c) prints the same hash.
            ulong hash = 14695981039346656037UL;
            foreach (Vector3 p in x)
            {
                foreach (float f in new[] { p.X, p.Y, p.Z })
                {
                    foreach (byte b in BitConverter.GetBytes(f)) hash = (hash ^ b) * 1099511628211UL;
                }
            }
            Console.WriteLine("positions hash " + hash.ToString("x16"));
            var stats = sheet.GetStats();
            Check(stats.MaxStrain < 0.15f, "the default solver holds the strain (" + stats.MaxStrain + ")");

            Cloth skirt = world.CreateCloth(new ClothDesc { Fabric = fabric.Id });
            skirt.SetSkin(1, 1, new int[skirt.ParticleCount], null);
            var reach = new float[skirt.ParticleCount];
            for (int i = 16; i < reach.Length; ++i) reach[i] = float.PositiveInfinity;
            skirt.SetMaxDistances(reach);
            skirt.SetJointMatrices(new[] { Matrix4x4.CreateTranslation(0.0f, 0.5f, 0.0f) });
            sheet.EnableContactWith(skirt, 0.01f);
            world.Step(1.0f / 60.0f);
            var s = new Vector3[skirt.ParticleCount];
            skirt.ReadPositions(s);
            Check(Math.Abs(s[3].Y - (start[3].Y + 0.5f)) < 1e-5f, "the skinned top row followed its joint 0.5 m up");
            Check(skirt.GetContactWith(sheet).Enabled, "contact between the two cloths is on");
        }
        return failures == 0 ? 0 : 1;
    }
}
