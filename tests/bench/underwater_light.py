#!/usr/bin/python3
"""The sky light that points under water keep: a CPU reference by path tracing (docs/liquid.md, "A camera under
water", item 2).

    tests/bench/underwater_light.py [--paths 200000] [--seed 1]

A square pool 1.6 wide with its floor at z = 0 and walls up to 0.6, filled with water to 0.45 (the light
benchmark's tank), under a uniform white sky of radiance 1 and nothing else. Floor and walls are Lambertian
with albedo 0.5; the water has a flat surface (IOR 1.33, Fresnel's equations, total internal reflection) and
Spindrift's default absorption. Paths start at receiver points (the floor's centre facing up, the middle of a
wall facing the pool at several depths) in cosine-weighted directions and bounce off the floor and walls (up
to 10 times); a path that refracts from the water into the air gains n² in radiance, one that refracts from
the air into the water keeps 1/n² of it. Prints, per receiver and channel, the irradiance with the water
over that without it, beside what Spindrift keeps today (0.934 exp(-sigma d 1.194), d the depth below the
surface) and the share of a uniform sky's light that Snell's window gives the receiver's orientation.
`--check` runs the tracer where closed-form optics knows the answer.
"""

import argparse

import numpy as np

IOR = 1.33
ABSORPTION = np.array([0.9, 0.3, 0.15])  # liquid.absorption_rgb's default, per unit length
HALF_WIDTH, WALL_HEIGHT, WATER_LEVEL = 0.8, 0.6, 0.45
ALBEDO = 0.5
BOUNCES = 10
HEMISPHERICAL_TRANSMITTANCE = 0.934  # lib/submerged_sky.glsl: 1 - 0.066
DIFFUSE_PATH_FACTOR = 1.194


def fresnel(cosine, n1, n2):
    """Unpolarised Fresnel reflectance for rays with incidence cosines `cosine` from index n1 into n2 (1 where
    the light is totally reflected) and the refracted cosine."""
    sine = n1 / n2 * np.sqrt(np.maximum(0.0, 1.0 - cosine * cosine))
    total = sine >= 1.0
    refracted = np.sqrt(np.maximum(0.0, 1.0 - sine * sine))
    rs = ((n1 * cosine - n2 * refracted) / (n1 * cosine + n2 * refracted)) ** 2
    rp = ((n1 * refracted - n2 * cosine) / (n1 * refracted + n2 * cosine)) ** 2
    return np.where(total, 1.0, 0.5 * (rs + rp)), refracted


def cosine_directions(normal, count, generator):
    """Cosine-weighted unit directions about `normal` (a unit vector)."""
    u1, u2 = generator.random(count), generator.random(count)
    radius, angle = np.sqrt(u1), 2.0 * np.pi * u2
    local = np.stack([radius * np.cos(angle), radius * np.sin(angle), np.sqrt(np.maximum(0.0, 1.0 - u1))], axis=1)
    helper = np.array([1.0, 0.0, 0.0]) if abs(normal[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    tangent = np.cross(helper, normal)
    tangent /= np.linalg.norm(tangent)
    bitangent = np.cross(normal, tangent)
    return local[:, :1] * tangent + local[:, 1:2] * bitangent + local[:, 2:] * normal


def cosine_directions_about(normals, generator):
    """One cosine-weighted direction about each row of `normals` (each along an axis)."""
    directions = np.empty_like(normals)
    for axis_normal in np.unique(normals, axis=0):
        rows = np.all(normals == axis_normal, axis=1)
        directions[rows] = cosine_directions(axis_normal, int(rows.sum()), generator)
    return directions


def trace(origins, directions, in_water, water, generator):
    """Radiance (per channel) along each path, with `water` filling the pool or not."""
    count = len(origins)
    throughput = np.ones((count, 3))
    radiance = np.zeros((count, 3))
    alive = np.ones(count, bool)
    for _ in range(BOUNCES * 3):
        if not alive.any():
            break
        o, d = origins[alive], directions[alive]
        wet = in_water[alive]
        # Distances to the pool's floor, its four walls (inside faces, up to WALL_HEIGHT) and the water's surface.
        with np.errstate(divide="ignore", invalid="ignore"):
            t_floor = np.where(d[:, 2] < 0, -o[:, 2] / d[:, 2], np.inf)
            t_wall = np.full(len(o), np.inf)
            wall_normal = np.zeros_like(o)
            for axis in (0, 1):
                for side in (-1.0, 1.0):
                    t = np.where(d[:, axis] * side > 0, (side * HALF_WIDTH - o[:, axis]) / d[:, axis], np.inf)
                    z = o[:, 2] + t * d[:, 2]
                    t = np.where((z >= 0.0) & (z <= WALL_HEIGHT), t, np.inf)
                    closer = t < t_wall
                    t_wall = np.where(closer, t, t_wall)
                    wall_normal[closer] = 0.0
                    wall_normal[closer, axis] = -side
            t_surface = np.where(water & (d[:, 2] != 0), (WATER_LEVEL - o[:, 2]) / d[:, 2], np.inf)
            t_surface = np.where((t_surface > 1e-9) & ((wet & (d[:, 2] > 0)) | (~wet & (d[:, 2] < 0))),
                                 t_surface, np.inf)
        t_hit = np.minimum(np.minimum(t_floor, t_wall), t_surface)
        index = np.nonzero(alive)[0]
        # Absorption over the segment in water.
        segment = np.where(np.isfinite(t_hit), t_hit, 0.0)
        throughput[index] *= np.where(wet[:, None], np.exp(-ABSORPTION * segment[:, None]), 1.0)
        escaped = ~np.isfinite(t_hit)  # up out of the pool: the sky (only rays in the air get here)
        radiance[index[escaped]] += throughput[index[escaped]]
        alive[index[escaped]] = False
        hit_point = o + np.where(np.isfinite(t_hit), t_hit, 0.0)[:, None] * d
        at_surface = np.isfinite(t_hit) & (t_surface <= np.minimum(t_floor, t_wall))
        at_solid = np.isfinite(t_hit) & ~at_surface
        # Diffuse bounce.
        solid_rows = index[at_solid]
        normals = np.where((t_floor <= t_wall)[at_solid, None], np.array([0.0, 0.0, 1.0]), wall_normal[at_solid])
        throughput[solid_rows] *= ALBEDO
        origins[solid_rows] = hit_point[at_solid] + 1e-7 * normals
        directions[solid_rows] = cosine_directions_about(normals, generator)
        # The surface: reflect or refract, chosen by Fresnel's reflectance.
        surface_rows = index[at_surface]
        from_water = wet[at_surface]
        incident = d[at_surface]
        cosine = np.abs(incident[:, 2])
        reflectance, refracted_cosine = fresnel(cosine, np.where(from_water, IOR, 1.0), np.where(from_water, 1.0, IOR))
        reflect = generator.random(len(surface_rows)) < reflectance
        new = incident.copy()
        new[reflect, 2] = -new[reflect, 2]
        ratio = np.where(from_water, IOR, 1.0 / IOR)
        refract = ~reflect
        new[refract, :2] = incident[refract, :2] * ratio[refract, None]
        new[refract, 2] = np.sign(incident[refract, 2]) * refracted_cosine[refract]
        # Radiance gains n^2 going from water into air along the path (the light comes the other way).
        throughput[surface_rows[refract]] *= np.where(from_water[refract], IOR * IOR, 1.0 / (IOR * IOR))[:, None]
        in_water[surface_rows[refract]] = ~from_water[refract]
        origins[surface_rows] = hit_point[at_surface] + 1e-7 * new
        directions[surface_rows] = new
        # Paths that bounced too often end dark.
    return radiance


def irradiance(point, normal, water, paths, generator):
    """Irradiance over pi (the mean radiance over cosine-weighted directions) at `point`, per channel."""
    origins = np.repeat(np.array(point, float)[None], paths, axis=0)
    directions = cosine_directions(np.array(normal, float), paths, generator)
    in_water = np.full(paths, water and point[2] < WATER_LEVEL)
    return trace(origins, directions, in_water, water, generator).mean(axis=0)


def snell_window_share(normal_z, steps=400):
    """The irradiance Snell's window gives a receiver whose normal makes cosine `normal_z` with the vertical,
    over what a uniform hemisphere of the same sky gives it (sky radiance n^2 (1 - F) inside the window)."""
    theta_air = (np.arange(steps) + 0.5) / steps * np.pi / 2
    phi = (np.arange(2 * steps) + 0.5) / (2 * steps) * 2 * np.pi
    theta_air, phi = np.meshgrid(theta_air, phi, indexing="ij")
    d_omega = np.sin(theta_air) * (np.pi / 2 / steps) * (np.pi / steps)
    mu = np.cos(theta_air)
    reflectance, _ = fresnel(mu, 1.0, IOR)
    theta_water = np.arcsin(np.sin(theta_air) / IOR)
    normal = np.array([np.sqrt(max(0.0, 1.0 - normal_z * normal_z)), 0.0, normal_z])
    direction = np.stack([np.sin(theta_water) * np.cos(phi), np.sin(theta_water) * np.sin(phi),
                          np.cos(theta_water)], axis=-1)
    cosine = np.maximum(direction @ normal, 0.0)
    return float(((1 - reflectance) * cosine * mu / np.cos(theta_water) * d_omega).sum() / np.pi)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--paths", type=int, default=200000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--check", action="store_true",
                        help="the tracer against closed-form optics: a pool 2,000 wide of clear water, whose floor "
                             "keeps 0.934 / (1 - albedo (1 - 0.934 / n^2)) of its light")
    arguments = parser.parse_args()
    global HALF_WIDTH, ABSORPTION
    if arguments.check:
        HALF_WIDTH, ABSORPTION = 1000.0, np.zeros(3)
    generator = np.random.default_rng(arguments.seed)
    receivers = [("floor, centre", (0.0, 0.0, 0.0), (0.0, 0.0, 1.0))]
    receivers += [(f"wall, {WATER_LEVEL - z:.2f} deep", (-HALF_WIDTH, 0.0, z), (1.0, 0.0, 0.0))
                  for z in (0.35, 0.25, 0.15, 0.05)]
    print(f"Snell's window, share of a uniform sky: facing up {snell_window_share(1.0):.3f}, 45 degrees "
          f"{snell_window_share(np.sqrt(0.5)):.3f}, vertical {snell_window_share(0.0):.3f}")
    print("| receiver | kept with water (R, G, B) | Spindrift's submerged term | dry E/pi | wet E/pi |")
    print("|---|---|---|---|---|")
    if arguments.check:
        receivers = receivers[:1]
        expected = HEMISPHERICAL_TRANSMITTANCE / (1.0 - ALBEDO * (1.0 - HEMISPHERICAL_TRANSMITTANCE / IOR ** 2))
        print(f"closed form for the floor: {expected:.3f}")
    for name, point, normal in receivers:
        dry = irradiance(point, normal, False, arguments.paths, generator)
        wet = irradiance(point, normal, True, arguments.paths, generator)
        depth = WATER_LEVEL - point[2]
        model = HEMISPHERICAL_TRANSMITTANCE * np.exp(-ABSORPTION * depth * DIFFUSE_PATH_FACTOR)
        fmt = lambda values: " / ".join(f"{v:.3f}" for v in values)
        print(f"| {name} | {fmt(wet / dry)} | {fmt(model)} | {fmt(dry)} | {fmt(wet)} |", flush=True)


if __name__ == "__main__":
    main()
