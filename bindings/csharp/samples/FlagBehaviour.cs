// The loop a Unity MonoBehaviour runs for a flag on a vehicle, without Unity:
// Awake creates the world, the flag and the chassis body it rides on;
// FixedUpdate moves the body to the chassis pose and steps the cloth;
// LateUpdate copies positions and normals into the mesh's vertex buffers;
// OnDestroy disposes the world. Main plays the engine: a fixed 50 Hz step
// (Unity's default Time.fixedDeltaTime) under a render loop of uneven frames,
// while the "vehicle" drives a course with a turn, a stop and a jump.
//
// In Unity the differences are: Vector3 for Float3 (same layout: read into
// a Vector3[] through MemoryMarshal.Cast<Vector3, float>, or into Float3[]
// and copy), mesh.SetVertices/SetNormals in LateUpdate, and the chassis pose
// from its Rigidbody (transform.position, transform.rotation: Unity's
// quaternions are x, y, z, w like the library's, but Unity is left-handed:
// flip z of positions and negate x and y of rotations, or keep the cloth in
// the vehicle's own frame).
using System;
using System.Diagnostics;
using ClothSharp;

sealed class FlagBehaviour : IDisposable
{
    const int Columns = 24, Rows = 16;
    const float Width = 1.2f, Height = 0.8f, PoleTop = 2.0f;

    World world;
    Cloth flag;
    Body chassis;
    readonly int[] poleColumn = new int[Rows];
    readonly float[] poleOffsets = new float[3 * Rows];

    // The mesh's buffers (Mesh.vertices / Mesh.normals in Unity), rewritten every rendered frame.
    public readonly Float3[] Vertices = new Float3[Columns * Rows];
    public readonly Float3[] Normals = new Float3[Columns * Rows];
    public int Steps;
    public double StepMilliseconds;
    public float MaxStrain;

    public void Awake(Float3 chassisPosition)
    {
        ClothLibrary.Verify();  // the native plugin matches these managed files
        ClothWorldDesc worldDesc = ClothWorldDesc.Default();
        worldDesc.WorkerCount = 2;
        world = new World(worldDesc);

        ClothBodyDesc bodyDesc = ClothBodyDesc.Default();
        bodyDesc.Position = chassisPosition;
        chassis = world.CreateBody(bodyDesc);
        // The pole, a capsule on the chassis, so the flag wraps around it rather than through it.
        ClothColliderDesc poleDesc = ClothColliderDesc.Default();
        poleDesc.Body = chassis.Id;
        poleDesc.LocalPosition = new Float3(0.0f, PoleTop - 0.6f, 0.0f);
        world.CreateCapsule(poleDesc, 0.03f, 0.6f);
        // The ground the vehicle drives on.
        world.CreatePlane(ClothColliderDesc.Default(), new Float3(0, 1, 0), 0.0f);

        // The flag streams backwards (-z) from the pole, its first column on the pole.
        ClothGridDesc grid = ClothGridDesc.Default();
        grid.Columns = Columns;
        grid.Rows = Rows;
        grid.Origin = new Float3(chassisPosition.X, chassisPosition.Y + PoleTop, chassisPosition.Z - 0.05f);
        grid.U = new Float3(0, 0, -Width);
        grid.V = new Float3(0, -Height, 0);
        using (Fabric fabric = world.CreateGridFabric(grid))
        {
            ClothDesc desc = ClothDesc.Default();
            desc.Fabric = fabric.Id;
            desc.AreaDensity = 0.15f;
            flag = world.CreateCloth(desc);
        }  // the cloth keeps the fabric alive
        for (int r = 0; r < Rows; ++r)
        {
            poleColumn[r] = r * Columns;
            poleOffsets[3 * r + 1] = PoleTop - Height * r / (Rows - 1);
            poleOffsets[3 * r + 2] = -0.05f;
        }
        flag.Attach(chassis, poleColumn, poleOffsets);
        ClothCarrierDesc carrier = ClothCarrierDesc.Default();
        carrier.TeleportDistance = 2.0f;  // a jump of more than 2 m in one step moves the flag along
        flag.SetCarrier(chassis, carrier);
        flag.SetWind(new Float3(1.0f, 0.0f, 0.5f));
    }

    public void FixedUpdate(float fixedDeltaTime, Float3 chassisPosition, Float4 chassisRotation, Float3 velocity)
    {
        chassis.SetPose(chassisPosition, chassisRotation);
        chassis.SetVelocity(velocity, new Float3(0, 0, 0));
        var clock = Stopwatch.StartNew();
        ClothStepOutcome r = world.Step(fixedDeltaTime);
        StepMilliseconds += clock.Elapsed.TotalMilliseconds;
        ++Steps;
        if (r != ClothStepOutcome.Ok) Console.WriteLine("step: " + r);
        MaxStrain = Math.Max(MaxStrain, flag.GetStats().MaxStrain);
    }

    public void Teleport(Float3 chassisPosition, Float4 chassisRotation) { chassis.Teleport(chassisPosition, chassisRotation); }

    public void LateUpdate()
    {
        flag.ReadPositions(Vertices);
        flag.ReadNormals(Normals);
    }

    // How far the pole column is from where the chassis holds it (it rides exactly on the body).
    public float PoleError(Float3 chassisPosition)
    {
        float error = 0.0f;
        for (int r = 0; r < Rows; ++r)
        {
            Float3 v = Vertices[poleColumn[r]];
            error = Math.Max(error, Math.Abs(v.X - chassisPosition.X));
            error = Math.Max(error, Math.Abs(v.Y - (chassisPosition.Y + poleOffsets[3 * r + 1])));
            error = Math.Max(error, Math.Abs(v.Z - (chassisPosition.Z + poleOffsets[3 * r + 2])));
        }
        return error;
    }

    public void OnDestroy() { Dispose(); }

    public void Dispose()
    {
        if (world != null) world.Dispose();  // the flag, the body and its colliders go with it
        world = null;
    }
}

static class FlagLoop
{
    // The course: 10 m/s along +x for 2 s, stop for 1 s, then a 20 m jump (a respawn) and 1 s more.
    static Float3 ChassisAt(double t, out Float3 velocity)
    {
        if (t < 2.0)
        {
            velocity = new Float3(10.0f, 0, 0);
            return new Float3((float)(10.0 * t), 0.5f, 0);
        }
        velocity = new Float3(0, 0, 0);
        if (t < 3.0) return new Float3(20.0f, 0.5f, 0);
        return new Float3(40.0f, 0.5f, 0);
    }

    static int Main()
    {
        const float fixedDeltaTime = 0.02f;
        var behaviour = new FlagBehaviour();
        Float3 velocity;
        var identity = new Float4(0, 0, 0, 1);
        behaviour.Awake(ChassisAt(0.0, out velocity));
        double time = 0.0, fixedTime = 0.0;
        int frames = 0;
        bool jumped = false, ok = true;
        float worstPole = 0.0f;
        var random = new Random(7);
        while (time < 4.0)
        {
            time += 0.012 + 0.012 * random.NextDouble();  // uneven render frames, 40-80 fps
            while (fixedTime + fixedDeltaTime <= time)  // Unity runs FixedUpdate to catch up
            {
                fixedTime += fixedDeltaTime;
                Float3 position = ChassisAt(fixedTime, out velocity);
                if (fixedTime >= 3.0 && !jumped)
                {
                    behaviour.Teleport(position, identity);
                    jumped = true;
                }
                behaviour.FixedUpdate(fixedDeltaTime, position, identity, velocity);
            }
            behaviour.LateUpdate();
            ++frames;
            Float3 now = ChassisAt(fixedTime, out velocity);
            worstPole = Math.Max(worstPole, behaviour.PoleError(now));
            if (frames % 60 == 0)
            {
                Float3 tip = behaviour.Vertices[23];
                Console.WriteLine(string.Format("t {0:F2} s: chassis x {1,5:F1}, flag tip ({2:F2}, {3:F2}, {4:F2}), max strain {5:F3}",
                                                fixedTime, now.X, tip.X, tip.Y, tip.Z, behaviour.MaxStrain));
            }
        }
        foreach (Float3 v in behaviour.Vertices)
        {
            ok &= !float.IsNaN(v.X + v.Y + v.Z) && !float.IsInfinity(v.X + v.Y + v.Z);
        }
        Float3 end = ChassisAt(fixedTime, out velocity);
        float trail = end.X - behaviour.Vertices[23].X;
        Console.WriteLine(string.Format("{0} frames, {1} fixed steps, {2:F3} ms a step, max strain {3:F3}, pole column within {4:E1} m, tip {5:F2} m from the pole after the jump",
                                        frames, behaviour.Steps, behaviour.StepMilliseconds / behaviour.Steps, behaviour.MaxStrain,
                                        worstPole, Math.Abs(trail)));
        behaviour.OnDestroy();
        ok &= behaviour.Steps == 200 && worstPole < 1e-4f && behaviour.MaxStrain < 0.5f && Math.Abs(trail) < 2.0f;
        Console.WriteLine(ok ? "flag loop: ok" : "flag loop: FAILED");
        return ok ? 0 : 1;
    }
}
