"""test_lights.py - point and spot lights as pyrender places them: cones, ranges, inverse-square falloff, errors."""
import math

import numpy as np
import pytest

import facet
from conftest import look_at

SIZE = 64  # pixels a side of the top views
EXTENT = 3.0  # the top views show x and z in [-EXTENT, EXTENT]


def floor(y=0.0, x0=-EXTENT, x1=EXTENT):
    """A floor facing +y at height y, over x0..x1 and the whole depth of the top view."""
    positions = np.array([[x0, y, -EXTENT], [x1, y, -EXTENT], [x1, y, EXTENT], [x0, y, EXTENT]], dtype=float)
    return facet.Mesh.from_arrays(positions, [[0, 2, 1], [0, 3, 2]], normals=np.tile([0.0, 1.0, 0.0], (4, 1)))


def top_view(meshes, light, light_pose):
    """The scene seen straight down by an orthographic camera, lit by one light and no ambient light; returns the
    colour, the depth and each pixel's world x and z (image right is +x, image up is -z)."""
    scene = facet.Scene(ambient_light=(0.0, 0.0, 0.0), bg_color=(0.0, 0.0, 0.0, 1.0))
    for mesh in meshes:
        scene.add(mesh)
    scene.add(facet.OrthographicCamera(xmag=EXTENT, ymag=EXTENT, znear=0.5, zfar=20.0),
              pose=look_at((0, 6, 0), (0, 0, 0), up=(0, 0, -1)))
    scene.add(light, pose=light_pose)
    color, depth = facet.OffscreenRenderer(SIZE, SIZE, threads=1, samples=1).render(scene)
    centres = (np.arange(SIZE) + 0.5) / SIZE * 2 * EXTENT - EXTENT
    x, z = np.meshgrid(centres, centres)
    return color.astype(int).sum(axis=-1), depth, x, z


def test_a_spot_light_lights_its_cone_and_nothing_outside():
    """A tilted spot: full light well inside the inner cone, none outside the outer one; it shines along its
    node's -z axis, so the disc lies where that axis points."""
    inner, outer = 0.25, 0.45
    position, target = np.array([-0.8, 2.0, 0.5]), np.array([0.4, 0.0, -0.3])
    light = facet.SpotLight(intensity=15.0, innerConeAngle=inner, outerConeAngle=outer)
    color, depth, x, z = top_view([floor()], light, look_at(position, target))
    assert np.all(depth > 0)
    to_point = np.stack([x, np.zeros_like(x), z], axis=-1) - position
    axis = (target - position) / np.linalg.norm(target - position)
    angle = np.arccos(np.clip(to_point @ axis / np.linalg.norm(to_point, axis=-1), -1, 1))
    inside, outside = angle < inner - 0.02, angle > outer + 0.02
    assert inside.sum() > 100 and outside.sum() > 1000
    assert np.all(color[inside] > 60)
    assert np.all(color[outside] == 0)


def test_a_point_light_falls_off_with_the_square_of_the_distance():
    """A floor 1 and 2 below the light: four times the intensity from twice as far looks the same right below it,
    and the same intensity looks darker."""
    pose = np.eye(4)
    pose[:3, 3] = (0, 3, 0)
    middle = (slice(SIZE // 2 - 1, SIZE // 2 + 1),) * 2  # the pixels nearest the point below the light
    near = top_view([floor(y=2.0)], facet.PointLight(intensity=0.8), pose)[0][middle]
    far = top_view([floor(y=1.0)], facet.PointLight(intensity=0.8 * 4.0), pose)[0][middle]
    dim = top_view([floor(y=1.0)], facet.PointLight(intensity=0.8), pose)[0][middle]
    assert near.min() > 100
    assert np.all(np.abs(near - far) <= 3)
    assert np.all(dim < near - 100)


def test_a_point_light_range_leaves_a_far_floor_unlit():
    """Two floors, a near one (left, 1 below the light) and a far one (right, 5 below): with a range of 3 the far
    floor gets none of the light; without one it is lit."""
    pose = np.eye(4)
    pose[:3, 3] = (-1.5, 1.0, 0.0)
    meshes = [floor(0.0, -EXTENT, 0.0), floor(-4.0, 0.0, EXTENT)]
    limited, depth, x, _ = top_view(meshes, facet.PointLight(intensity=20.0, range=3.0), pose)
    unlimited, _, _, _ = top_view(meshes, facet.PointLight(intensity=20.0), pose)
    near, far = (x < -0.1) & (depth > 0), (x > 0.1) & (depth > 0)
    assert near.sum() > 1000 and far.sum() > 1000
    assert limited[near].max() > 150
    assert np.all(limited[far] == 0)
    assert unlimited[far].min() > 10


def test_a_directional_light_is_irradiance_in_lux():
    """colour x intensity is the irradiance: doubling one or the other gives the same picture."""
    down = look_at((0, 1, 0), (0, 0, 0), up=(0, 0, -1))
    a = top_view([floor()], facet.DirectionalLight(color=(0.5, 0.5, 0.5), intensity=2.0), down)[0]
    b = top_view([floor()], facet.DirectionalLight(color=(1.0, 1.0, 1.0), intensity=1.0), down)[0]
    c = top_view([floor()], facet.DirectionalLight(intensity=2.0), down)[0]
    np.testing.assert_array_equal(a, b)
    assert c.min() > b.max() + 30


@pytest.mark.parametrize("make, message", [
    (lambda: facet.PointLight(intensity=-1.0), "intensity"),
    (lambda: facet.PointLight(intensity=float("nan")), "intensity"),
    (lambda: facet.DirectionalLight(intensity=float("inf")), "intensity"),
    (lambda: facet.SpotLight(intensity=-0.5), "intensity"),
    (lambda: facet.PointLight(range=0.0), "range"),
    (lambda: facet.PointLight(range=-2.0), "range"),
    (lambda: facet.SpotLight(range=float("nan")), "range"),
    (lambda: facet.SpotLight(innerConeAngle=0.6, outerConeAngle=0.5), "innerConeAngle"),
    (lambda: facet.SpotLight(innerConeAngle=-0.1), "innerConeAngle"),
    (lambda: facet.SpotLight(outerConeAngle=math.pi / 2 + 0.01), "outerConeAngle"),
    (lambda: facet.SpotLight(outerConeAngle=-0.1), "outerConeAngle"),
    (lambda: facet.SpotLight(color=(1.0, 0.0)), "color"),
])
def test_bad_light_values_raise_value_error(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_pyrenders_defaults_and_a_right_angle_cone():
    spot = facet.SpotLight(outerConeAngle=math.pi / 2)
    assert spot.innerConeAngle == 0.0 and spot.outerConeAngle == math.pi / 2 and spot.range is None
    assert facet.SpotLight().outerConeAngle == pytest.approx(math.pi / 4)
    assert facet.PointLight(range=float("inf")).range == math.inf  # unlimited, as None
    scene = facet.Scene()
    node = scene.add(spot, pose=np.eye(4))
    assert scene.light_nodes == {node} and node.light is spot


def test_shadow_flags_let_directional_and_spot_lights_cast_shadows():
    """A small plate above the floor and a directional light at 45 degrees: SHADOWS_DIRECTIONAL darkens the floor
    where the plate hides the light (beside the plate, as the camera looks straight down) and nowhere else;
    SHADOWS_SPOT leaves a directional light unshadowed."""
    plate = facet.Mesh.from_arrays(np.array([[-0.5, 1.0, -0.5], [0.5, 1.0, -0.5], [0.5, 1.0, 0.5], [-0.5, 1.0, 0.5]], dtype=float),
                       [[0, 2, 1], [0, 3, 2]], normals=np.tile([0.0, 1.0, 0.0], (4, 1)))
    sun = look_at((1.0, 1.0, 0.0), (0.0, 0.0, 0.0))  # shines along -z of its pose: towards -x, down
    scene = facet.Scene(ambient_light=(0.0, 0.0, 0.0), bg_color=(0.0, 0.0, 0.0, 1.0))
    scene.add(floor())
    scene.add(plate)
    scene.add(facet.OrthographicCamera(xmag=EXTENT, ymag=EXTENT, znear=0.5, zfar=20.0),
              pose=look_at((0, 6, 0), (0, 0, 0), up=(0, 0, -1)))
    scene.add(facet.DirectionalLight(intensity=3.0), pose=sun)
    renderer = facet.OffscreenRenderer(SIZE, SIZE, threads=1, samples=1)
    plain = renderer.render(scene)[0].astype(int).sum(axis=-1)
    shadowed = renderer.render(scene, flags=facet.RenderFlags.SHADOWS_DIRECTIONAL)[0].astype(int).sum(axis=-1)
    spot_only = renderer.render(scene, flags=facet.RenderFlags.SHADOWS_SPOT)[0].astype(int).sum(axis=-1)
    centres = (np.arange(SIZE) + 0.5) / SIZE * 2 * EXTENT - EXTENT
    x, z = np.meshgrid(centres, centres)
    # The plate at height 1 throws its shadow 1 towards -x: x in [-1.5, -0.5], z in [-0.5, 0.5].
    in_shadow = (x > -1.4) & (x < -0.6) & (np.abs(z) < 0.4)
    open_floor = (x > 1.0) | (np.abs(z) > 1.0)
    assert in_shadow.sum() > 20
    assert np.all(shadowed[in_shadow] < plain[in_shadow] // 4)
    assert np.array_equal(shadowed[open_floor], plain[open_floor])
    assert np.array_equal(spot_only, plain)
