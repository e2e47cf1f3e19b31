// ClothSharp's UNITY_5_3_OR_NEWER branches, compiled against the UnityEngine
// stub (UnityEngineStub.cs) and run under Mono: Unity's Vector3, Quaternion
// and Matrix4x4 in and out of the binding, IL2CPP's AOT callback attribute,
// and the Unity sample (samples/unity/ClothFlag.cs) driven through its
// messages as Unity calls them. Exits non-zero on the first failed check.
using System;
using System.Reflection;
using ClothSharp;
using UnityEngine;

static class UnityTests
{
    static int checks;

    static void Check(bool condition, string what)
    {
        if (!condition) throw new Exception("FAILED: " + what);
        ++checks;
        Console.WriteLine("ok - " + what);
    }

    static bool Finite(Vector3 v)
    {
        return !float.IsNaN(v.x + v.y + v.z) && !float.IsInfinity(v.x + v.y + v.z);
    }

    static int Main()
    {
        try
        {
            UnityTypes();
            Callbacks();
            Sample();
            Console.WriteLine("Unity branches: all " + checks + " checks passed");
            return 0;
        }
        catch (Exception e)
        {
            Console.WriteLine(e);
            return 1;
        }
    }

    static void UnityTypes()
    {
        Float3 f = new Vector3(1.0f, 2.0f, 3.0f);
        Vector3 back = f;
        Check(f.Y == 2.0f && back.z == 3.0f, "Float3 converts to and from UnityEngine.Vector3");
        using (var world = new World())
        {
            Cloth cloth = world.CreateCloth(world.CreateGridFabric(new ClothGridDesc { Columns = 4, Rows = 4 }));
            var rest = new Vector3[16];
            var xyz = new float[48];
            cloth.ReadPositions(rest);
            cloth.ReadPositions(xyz);
            Check(rest[5].x == xyz[15] && rest[5].y == xyz[16] && rest[5].z == xyz[17],
                  "ReadPositions(UnityEngine.Vector3[]) reads in place what float[] reads");
            cloth.SetSkin(1, 1, new int[16], null);
            cloth.SetMaxDistances(new float[16]);
            cloth.SetJointMatrices(new[] { Matrix4x4.Translate(new Vector3(0.0f, 1.0f, 0.0f)) });
            world.Step(1.0f / 60.0f);
            var x = new Vector3[16];
            cloth.ReadPositions(x);
            Check(Math.Abs(x[5].y - (rest[5].y + 1.0f)) < 1e-5f && Math.Abs(x[5].x - rest[5].x) < 1e-5f,
                  "SetJointMatrices(UnityEngine.Matrix4x4[]): Matrix4x4.Translate(0, 1, 0) lifts the skin 1 m");
            Body body = world.CreateBody(new Vector3(1.0f, 2.0f, 3.0f), Quaternion.identity);
            Vector3 p;
            Quaternion q;
            body.GetPose(out p, out q);
            Check(p.x == 1.0f && p.z == 3.0f && q.w == 1.0f, "Body from and to UnityEngine.Vector3 and Quaternion");
        }
    }

    // Under Unity the callbacks carry AOT.MonoPInvokeCallbackAttribute (what IL2CPP looks for), and the
    // binding defines no attribute of its own.
    static void Callbacks()
    {
        Type callbacks = typeof(World).GetNestedType("Callbacks", BindingFlags.NonPublic);
        int marked = 0, methods = 0;
        foreach (MethodInfo m in callbacks.GetMethods(BindingFlags.NonPublic | BindingFlags.Static))
        {
            if (m.IsSpecialName || m.Name.StartsWith("Of")) continue;
            ++methods;
            if (m.GetCustomAttributes(typeof(AOT.MonoPInvokeCallbackAttribute), false).Length == 1) ++marked;
        }
        Check(methods >= 5 && marked == methods, "every native callback is marked with AOT.MonoPInvokeCallback (" + marked + ")");
        Check(typeof(World).Assembly.GetType("ClothSharp.MonoPInvokeCallbackAttribute") == null,
              "the Unity build defines no MonoPInvokeCallbackAttribute of its own");
        Check(Native.Library == "cloth", "the desktop Unity build imports \"cloth\"");
    }

    static void Invoke(object target, string message)
    {
        target.GetType().GetMethod(message, BindingFlags.Instance | BindingFlags.NonPublic).Invoke(target, null);
    }

    // The sample as Unity drives it: Awake, then FixedUpdate at 50 Hz and LateUpdate per frame while
    // the pole moves along x, then OnDestroy.
    static void Sample()
    {
        var flag = new ClothFlag();
        flag.transform.position = new Vector3(0.0f, 2.0f, 0.0f);
        Invoke(flag, "Awake");
        Mesh mesh = flag.GetComponent<MeshFilter>().mesh;
        Check(mesh != null && mesh.triangles.Length == 3 * 2 * 23 * 15 && mesh.vertices.Length == 24 * 16,
              "Awake builds the mesh: 384 vertices, 690 triangles");
        for (int frame = 0; frame < 100; ++frame)
        {
            flag.transform.position = new Vector3(0.02f * frame, 2.0f, 0.0f);
            Invoke(flag, "FixedUpdate");
            Invoke(flag, "LateUpdate");
        }
        bool finite = true;
        foreach (Vector3 v in mesh.vertices) finite &= Finite(v);
        Vector3 top = mesh.vertices[0], tip = mesh.vertices[23];
        Check(finite && mesh.normals.Length == 384 && mesh.Bounds == 100, "100 frames: finite vertices and normals written to the mesh");
        Check(Math.Abs(top.x - 1.98f) < 1e-4f && Math.Abs(top.y - 2.0f) < 1e-4f,
              "the flag's first column rides the pole (x " + top.x + ")");
        Check(tip.y < 2.0f && flag.LastOutcome == ClothStepOutcome.Ok, "the free tip hangs below the pole top (y " + tip.y + ")");
        Invoke(flag, "OnDestroy");
    }
}
