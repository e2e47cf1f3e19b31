// A flag for Unity: add it to a GameObject with a MeshFilter and a
// MeshRenderer at the top of a pole. Awake makes the world, the flag and a
// body that follows this transform (the flag's first column hangs on it);
// FixedUpdate moves the body and steps; LateUpdate writes positions and
// normals straight into the mesh's Vector3 arrays (no copy in between);
// OnDestroy disposes the world. Unity's Vector3, Quaternion and Matrix4x4
// go to ClothSharp as they are (same layouts).
//
// Unity is left-handed and the library does not care which hand a frame
// has (gravity is -y in both), so positions and rotations pass unchanged;
// only the triangles' winding is reversed for Unity's clockwise front faces,
// and the normals turned with it.
#if UNITY_5_3_OR_NEWER
using ClothSharp;
using UnityEngine;

[RequireComponent(typeof(MeshFilter))]
public sealed class ClothFlag : MonoBehaviour
{
    public int columns = 24;
    public int rows = 16;
    public float width = 1.2f;
    public float height = 0.8f;
    public Vector3 wind = new Vector3(4.0f, 0.0f, 1.0f);

    World world;
    Cloth flag;
    Body pole;
    Mesh mesh;
    Vector3[] vertices;
    Vector3[] normals;

    /// <summary>The last step's outcome (Ok unless a budget or solver limit was met).</summary>
    public ClothStepOutcome LastOutcome { get; private set; }
    public Vector3[] Vertices { get { return vertices; } }

    void Awake()
    {
        ClothLibrary.Verify();  // the plugin matches these managed files
        world = new World();
        pole = world.CreateBody(transform.position, transform.rotation);
        // The flag streams along +x from the pole, its first column on it.
        Fabric fabric = world.CreateGridFabric(new ClothGridDesc
        {
            Columns = (uint)columns,
            Rows = (uint)rows,
            Origin = transform.position,
            U = new Vector3(width, 0.0f, 0.0f),
            V = new Vector3(0.0f, -height, 0.0f),
        });
        flag = world.CreateCloth(fabric);
        var column = new int[rows];
        for (int r = 0; r < rows; ++r) column[r] = r * columns;
        flag.Attach(pole, column);
        flag.SetWind(wind);

        var triangles = new int[3 * fabric.TriangleCount];
        fabric.ReadTriangles(triangles);
        for (int t = 0; t < triangles.Length; t += 3)
        {
            int swap = triangles[t + 1];
            triangles[t + 1] = triangles[t + 2];
            triangles[t + 2] = swap;
        }
        vertices = new Vector3[flag.ParticleCount];
        normals = new Vector3[flag.ParticleCount];
        flag.ReadPositions(vertices);
        mesh = new Mesh();
        mesh.MarkDynamic();
        mesh.vertices = vertices;
        mesh.triangles = triangles;
        GetComponent<MeshFilter>().mesh = mesh;
    }

    void FixedUpdate()
    {
        pole.SetPose(transform.position, transform.rotation);
        LastOutcome = world.Step(Time.fixedDeltaTime);
        if (LastOutcome != ClothStepOutcome.Ok) Debug.LogWarning("cloth step: " + LastOutcome);
    }

    void LateUpdate()
    {
        flag.ReadPositions(vertices);
        flag.ReadNormals(normals);
        for (int i = 0; i < normals.Length; ++i) normals[i] = new Vector3(-normals[i].x, -normals[i].y, -normals[i].z);
        mesh.vertices = vertices;
        mesh.normals = normals;
        mesh.RecalculateBounds();
    }

    void OnDestroy()
    {
        if (world != null) world.Dispose();
    }
}
#endif
