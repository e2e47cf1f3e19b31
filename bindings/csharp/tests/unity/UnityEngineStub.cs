// The few UnityEngine and AOT types ClothSharp's UNITY_5_3_OR_NEWER branches
// and the Unity sample use, with Unity's names and layouts, so that those
// branches compile and run under Mono in the test command (no Unity here).
// Vector3 (x, y, z), Quaternion (x, y, z, w) and Matrix4x4 (column-major
// fields m00, m10, m20, m30, m01, ...) have Unity's field order, which is
// what the binding relies on. Behaviour is minimal: what the sample calls.
using System;
using System.Collections.Generic;

namespace AOT
{
    [AttributeUsage(AttributeTargets.Method)]
    public sealed class MonoPInvokeCallbackAttribute : Attribute
    {
        public MonoPInvokeCallbackAttribute(Type type) { }
    }
}

namespace UnityEngine
{
    public struct Vector3
    {
        public float x, y, z;
        public Vector3(float x, float y, float z) { this.x = x; this.y = y; this.z = z; }
        public static Vector3 zero { get { return new Vector3(0, 0, 0); } }
        public override string ToString() { return "(" + x + ", " + y + ", " + z + ")"; }
    }

    public struct Quaternion
    {
        public float x, y, z, w;
        public Quaternion(float x, float y, float z, float w) { this.x = x; this.y = y; this.z = z; this.w = w; }
        public static Quaternion identity { get { return new Quaternion(0, 0, 0, 1); } }
    }

    public struct Matrix4x4
    {
        public float m00, m10, m20, m30, m01, m11, m21, m31, m02, m12, m22, m32, m03, m13, m23, m33;
        public static Matrix4x4 identity { get { return new Matrix4x4 { m00 = 1, m11 = 1, m22 = 1, m33 = 1 }; } }
        public static Matrix4x4 Translate(Vector3 v)
        {
            Matrix4x4 m = identity;
            m.m03 = v.x;
            m.m13 = v.y;
            m.m23 = v.z;
            return m;
        }
    }

    public class Object { }

    public class Component : Object
    {
        readonly Dictionary<Type, Component> components = new Dictionary<Type, Component>();
        Transform own;
        public Transform transform { get { return own ?? (own = this as Transform ?? new Transform()); } }
        public T GetComponent<T>() where T : Component, new()
        {
            Component c;
            if (!components.TryGetValue(typeof(T), out c)) components[typeof(T)] = c = new T();
            return (T)c;
        }
    }

    public class Behaviour : Component { public bool enabled = true; }
    public class MonoBehaviour : Behaviour { }

    public class Transform : Component
    {
        public Vector3 position;
        public Quaternion rotation = Quaternion.identity;
    }

    public sealed class Mesh : Object
    {
        public Vector3[] vertices;
        public Vector3[] normals;
        public int[] triangles;
        public int Bounds;
        public void MarkDynamic() { }
        public void RecalculateBounds() { ++Bounds; }
    }

    public sealed class MeshFilter : Component
    {
        public Mesh mesh;
    }

    public static class Time
    {
        public static float fixedDeltaTime = 0.02f;
    }

    public static class Debug
    {
        public static void LogWarning(object message) { Console.WriteLine("warning: " + message); }
    }

    [AttributeUsage(AttributeTargets.Class)]
    public sealed class RequireComponent : Attribute
    {
        public RequireComponent(Type type) { }
    }
}
