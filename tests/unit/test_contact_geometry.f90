!> Contact geometry kernels: facets and corner areas sum to the segment area (planar
!> and warped segments), facet orientation, the warped-segment rule against the
!> bilinear surface area (Gauss quadrature), and triangle overlaps: analytic cases,
!> degenerate input, projection, rigid motions, and random pairs against an
!> independent exact reference (vertex/edge-intersection hull) and scanlines.
program test_contact_geometry
  use, intrinsic :: iso_fortran_env, only: output_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use core_kinds, only: rk
  use mesh_geometry, only: quad_vector_area
  use contact_geometry, only: segment_facets, segment_area, corner_areas, quad_unit_normal, &
      triangle_vector_area, triangle_unit_normal, triangle_overlap, triangle_overlap_area, &
      SEGMENT_FACET_COUNT, FACET_CORNER
  use check, only: check_true, check_close, check_summary
  implicit none
  real(rk), parameter :: eps = epsilon(1.0_rk)
  real(rk), parameter :: pi = 3.14159265358979323846264338327950288_rk
  !> Gauss-Legendre order for the bilinear surface area.
  integer, parameter :: GAUSS_ORDER = 24
  real(rk) :: gauss_x(GAUSS_ORDER), gauss_w(GAUSS_ORDER)

  call set_seed()
  call gauss_legendre(GAUSS_ORDER, gauss_x, gauss_w)
  call test_square_segments()
  call test_random_segments()
  call test_warp_order()
  call test_facet_orientation()
  call test_overlap_analytic()
  call test_overlap_degenerate()
  call test_overlap_projection()
  call test_overlap_random()
  call test_overlap_near_degenerate()
  call test_overlap_partition()
  call check_summary()

contains

  subroutine set_seed()
    integer :: seed_size
    integer, allocatable :: seed(:)
    call random_seed(size=seed_size)
    allocate(seed(seed_size))
    seed = 271828
    call random_seed(put=seed)
  end subroutine set_seed

  !> Unit square, unit square warped by +h, -h, +h, -h (analytic areas), and a
  !> rectangle (equal corner areas).
  subroutine test_square_segments()
    real(rk) :: p(3, 4), area(4), normal(3), h, bilinear
    p = square(0.0_rk)
    call check_close('unit square: segment area', segment_area(p), 1.0_rk, 4 * eps)
    call corner_areas(p, area)
    call check_close('unit square: corner area 1', area(1), 0.25_rk, 4 * eps)
    call check_close('unit square: corner area 3', area(3), 0.25_rk, 4 * eps)
    normal = quad_unit_normal(p)
    call check_close('unit square: normal z', normal(3), 1.0_rk, 4 * eps)
    call check_close('unit square: bilinear area (Gauss)', bilinear_area(p), 1.0_rk, 16 * eps)

    p = square(0.0_rk)
    p(1, :) = 3.0_rk * p(1, :)
    p(2, :) = 0.5_rk * p(2, :)
    call corner_areas(p, area)
    call check_close('3 x 0.5 rectangle: corner areas equal', maxval(area) - minval(area), &
        0.0_rk, 0.0_rk, atol=8 * eps)
    call check_close('3 x 0.5 rectangle: segment area', segment_area(p), 1.5_rk, 4 * eps)

    h = 0.1_rk
    p = square(h)
    call check_close('warped square h=0.1: segment area = sqrt(1+4h^2)', segment_area(p), &
        sqrt(1.0_rk + 4.0_rk * h**2), 8 * eps)
    call check_close('warped square h=0.1: |vector area| = 1', norm2(quad_vector_area(p)), &
        1.0_rk, 4 * eps)
    call corner_areas(p, area)
    call check_close('warped square h=0.1: corner areas sum', sum(area), segment_area(p), &
        4 * eps)
    bilinear = bilinear_area(p)
    write(output_unit, '(a,es12.4)') 'info warped square h=0.1: segment - bilinear area =', &
        segment_area(p) - bilinear
    h = 0.01_rk
    p = square(h)
    call check_close('warped square: (segment - bilinear)/h^2 -> 2/3 at h=0.01', &
        (segment_area(p) - bilinear_area(p)) / h**2, 2.0_rk / 3.0_rk, 1.0e-3_rk)
  end subroutine test_square_segments

  !> Random planar and warped convex segments: facets, corners and the vector area.
  subroutine test_random_segments()
    integer, parameter :: trials = 500
    real(rk) :: p(3, 4), facets(3, 3, SEGMENT_FACET_COUNT), area(4), vector(3), total
    real(rk) :: seg, warp, max_facet, max_corner, max_vector, max_planar, max_bilinear
    real(rk) :: min_excess
    integer :: trial, f

    max_facet = 0.0_rk
    max_corner = 0.0_rk
    max_vector = 0.0_rk
    max_planar = 0.0_rk
    max_bilinear = 0.0_rk
    min_excess = huge(1.0_rk)
    do trial = 1, trials
      if (mod(trial, 2) == 0) then
        warp = 0.0_rk
      else
        warp = 0.3_rk * random_real()
      end if
      p = random_convex_quad(warp)
      seg = segment_area(p)
      call segment_facets(p, facets)
      total = 0.0_rk
      vector = 0.0_rk
      do f = 1, SEGMENT_FACET_COUNT
        total = total + norm2(triangle_vector_area(facets(:, :, f)))
        vector = vector + triangle_vector_area(facets(:, :, f))
      end do
      call corner_areas(p, area)
      max_facet = max(max_facet, abs(total - seg) / seg)
      max_corner = max(max_corner, abs(sum(area) - seg) / seg)
      max_vector = max(max_vector, norm2(vector - quad_vector_area(p)) / seg)
      min_excess = min(min_excess, (seg - norm2(quad_vector_area(p))) / seg)
      if (warp == 0.0_rk) then
        max_planar = max(max_planar, abs(seg - norm2(quad_vector_area(p))) / seg)
        max_bilinear = max(max_bilinear, abs(seg - bilinear_area(p)) / seg)
      end if
    end do
    call check_close('random segments: facets sum to segment area (max rel diff)', max_facet, &
        0.0_rk, 0.0_rk, atol=16 * eps)
    call check_close('random segments: corner areas sum to segment area', max_corner, &
        0.0_rk, 0.0_rk, atol=16 * eps)
    call check_close('random segments: facet vector areas sum to quad_vector_area', &
        max_vector, 0.0_rk, 0.0_rk, atol=32 * eps)
    call check_true('random segments: segment area >= |vector area|', &
        min_excess >= -16 * eps)
    call check_close('random planar segments: segment area = |vector area|', max_planar, &
        0.0_rk, 0.0_rk, atol=32 * eps)
    call check_close('random planar segments: segment area = bilinear area', max_bilinear, &
        0.0_rk, 0.0_rk, atol=1.0e-13_rk)
  end subroutine test_random_segments

  !> The difference from the bilinear surface area is second order in the warp:
  !> halving the warp divides it by 4.
  subroutine test_warp_order()
    integer, parameter :: trials = 50
    real(rk), parameter :: h = 0.01_rk
    real(rk), parameter :: alternate(4) = [1.0_rk, -1.0_rk, 1.0_rk, -1.0_rk]
    real(rk) :: p0(3, 4), p(3, 4), normal(3), size, d1, d2, worst, low, high
    integer :: trial, k
    character(len=100) :: line

    worst = 0.0_rk
    low = huge(1.0_rk)
    high = -huge(1.0_rk)
    do trial = 1, trials
      p0 = random_convex_quad(0.0_rk)
      normal = quad_unit_normal(p0)
      size = sqrt(segment_area(p0))
      do k = 1, 4
        p(:, k) = p0(:, k) + h * size * alternate(k) * normal
      end do
      d1 = (segment_area(p) - bilinear_area(p)) / size**2
      do k = 1, 4
        p(:, k) = p0(:, k) + 0.5_rk * h * size * alternate(k) * normal
      end do
      d2 = (segment_area(p) - bilinear_area(p)) / size**2
      worst = max(worst, abs(d1 / d2 - 4.0_rk))
      low = min(low, d1 / h**2)
      high = max(high, d1 / h**2)
    end do
    call check_close('warped segments: difference ratio h/(h/2) = 4 (max |ratio - 4|)', &
        worst, 0.0_rk, 0.0_rk, atol=0.01_rk)
    write(line, '(a,f8.4,a,f8.4)') '(segment - bilinear)/(h^2 size^2) at h=0.01 from', low, &
        ' to', high
    write(output_unit, '(a)') 'info '//trim(line)
  end subroutine test_warp_order

  !> All 8 facets of a convex segment (planar, or slightly warped) point along its
  !> normal, and each facet starts at its owning corner.
  subroutine test_facet_orientation()
    integer, parameter :: trials = 500
    real(rk) :: p(3, 4), facets(3, 3, SEGMENT_FACET_COUNT), normal(3), smallest
    logical :: owners
    integer :: trial, f

    smallest = huge(1.0_rk)
    owners = .true.
    do trial = 1, trials
      p = random_convex_quad(merge(0.0_rk, 0.05_rk * random_real(), mod(trial, 2) == 0))
      normal = quad_unit_normal(p)
      call segment_facets(p, facets)
      do f = 1, SEGMENT_FACET_COUNT
        smallest = min(smallest, dot_product(triangle_unit_normal(facets(:, :, f)), normal))
        owners = owners .and. all(facets(:, 1, f) == p(:, FACET_CORNER(f)))
      end do
    end do
    call check_true('convex segments: all 8 facets oriented along the normal', smallest > 0)
    call check_true('facets 2k-1, 2k start at corner k (FACET_CORNER)', owners)
  end subroutine test_facet_orientation

  !> Analytic overlaps in the plane z = 0, then moved rigidly in 3D.
  subroutine test_overlap_analytic()
    real(rk), parameter :: z(3) = [0.0_rk, 0.0_rk, 1.0_rk]
    real(rk) :: a(3, 3), b(3, 3), big(3, 3), area, centroid(3), r, rotation(3, 3), shift(3)
    real(rk) :: star1(3, 3), star2(3, 3)
    integer :: k

    a = triangle(0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk, 1.0_rk)
    call triangle_overlap(a, a, z, area, centroid)
    call check_close('identical: area', area, 0.5_rk, 4 * eps)
    call check_close('identical: centroid', norm2(centroid - [1, 1, 0] / 3.0_rk), 0.0_rk, &
        0.0_rk, atol=4 * eps)

    b = translated(a, [2.0_rk, 0.0_rk, 0.0_rk])
    call check_close('disjoint (apart): 0', triangle_overlap_area(a, b, z), 0.0_rk, 0.0_rk, &
        atol=tiny(1.0_rk))
    b = triangle(1.0_rk, 1.0_rk, 0.6_rk, 1.0_rk, 1.0_rk, 0.6_rk)
    call check_close('disjoint (bounding boxes overlap): 0', triangle_overlap_area(a, b, z), &
        0.0_rk, 0.0_rk, atol=tiny(1.0_rk))

    big = triangle(-1.0_rk, -1.0_rk, 3.0_rk, -1.0_rk, -1.0_rk, 3.0_rk)
    call triangle_overlap(big, a, z, area, centroid)
    call check_close('nested (inner clipped by outer): inner area', area, 0.5_rk, 8 * eps)
    call check_close('nested: inner centroid', norm2(centroid - [1, 1, 0] / 3.0_rk), 0.0_rk, &
        0.0_rk, atol=8 * eps)
    call check_close('nested (outer clipped by inner): inner area', &
        triangle_overlap_area(a, big, z), 0.5_rk, 8 * eps)

    b = triangle(0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 1.0_rk, 1.0_rk)
    call triangle_overlap(a, b, z, area, centroid)
    call check_close('half overlap of right triangles: 1/4', area, 0.25_rk, 4 * eps)
    call check_close('half overlap: centroid (1/2, 1/6)', &
        norm2(centroid - [0.5_rk, 1.0_rk / 6.0_rk, 0.0_rk]), 0.0_rk, 0.0_rk, atol=4 * eps)
    call check_close('half overlap, a clockwise', triangle_overlap_area(a(:, [1, 3, 2]), b, z), &
        0.25_rk, 4 * eps)
    call check_close('half overlap, b clockwise', triangle_overlap_area(a, b(:, [3, 2, 1]), z), &
        0.25_rk, 4 * eps)
    call check_close('half overlap, both clockwise', &
        triangle_overlap_area(a(:, [2, 1, 3]), b(:, [1, 3, 2]), z), 0.25_rk, 4 * eps)
    call check_close('half overlap, b cyclically shifted', &
        triangle_overlap_area(a, b(:, [2, 3, 1]), z), 0.25_rk, 4 * eps)
    call check_close('half overlap, normal reversed', triangle_overlap_area(a, b, -z), &
        0.25_rk, 4 * eps)
    call check_close('half overlap, normal not unit (5 z)', &
        triangle_overlap_area(a, b, 5.0_rk * z), 0.25_rk, 4 * eps)

    b = translated(a, [0.5_rk, 0.0_rk, 0.0_rk])
    call triangle_overlap(a, b, z, area, centroid)
    call check_close('right triangle shifted by half a leg: 1/8', area, 0.125_rk, 4 * eps)
    call check_close('shifted: centroid (2/3, 1/6)', &
        norm2(centroid - [2.0_rk / 3.0_rk, 1.0_rk / 6.0_rk, 0.0_rk]), 0.0_rk, 0.0_rk, &
        atol=4 * eps)

    ! Star of David: the hexagon is 2/3 of either triangle, sqrt(3)/2 for radius 1.
    do k = 1, 3
      r = 2.0_rk * pi * (k - 1) / 3.0_rk + 0.5_rk * pi
      star1(:, k) = [cos(r), sin(r), 0.0_rk]
      star2(:, k) = [cos(r + pi), sin(r + pi), 0.0_rk]
    end do
    call triangle_overlap(star1, star2, z, area, centroid)
    call check_close('star of David: hexagon sqrt(3)/2', area, sqrt(3.0_rk) / 2.0_rk, 8 * eps)
    call check_close('star of David: centroid at centre', norm2(centroid), 0.0_rk, 0.0_rk, &
        atol=8 * eps)

    b = triangle(1.0_rk, 0.0_rk, 1.0_rk, 1.0_rk, 0.0_rk, 1.0_rk)
    call check_close('shared edge: 0', triangle_overlap_area(a, b, z), 0.0_rk, 0.0_rk, &
        atol=4 * eps)
    call check_close('shared edge, roles swapped: 0', triangle_overlap_area(b, a, z), 0.0_rk, &
        0.0_rk, atol=4 * eps)
    b = triangle(1.0_rk, 0.0_rk, 2.0_rk, 0.0_rk, 2.0_rk, 1.0_rk)
    call check_close('touching at a vertex: 0', triangle_overlap_area(a, b, z), 0.0_rk, &
        0.0_rk, atol=4 * eps)
    call check_close('touching at a vertex, roles swapped: 0', triangle_overlap_area(b, a, z), &
        0.0_rk, 0.0_rk, atol=4 * eps)
    b = triangle(0.5_rk, 0.5_rk, 1.5_rk, 0.5_rk, 0.5_rk, 1.5_rk)
    call check_close('vertex touching the hypotenuse: 0', triangle_overlap_area(a, b, z), &
        0.0_rk, 0.0_rk, atol=4 * eps)

    ! The half-overlap case moved rigidly in 3D.
    rotation = random_rotation()
    shift = 100.0_rk * (random_vector() - 0.5_rk)
    b = triangle(0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 1.0_rk, 1.0_rk)
    call triangle_overlap(moved(a, rotation, shift), moved(b, rotation, shift), &
        matmul(rotation, z), area, centroid)
    call check_close('half overlap rotated and translated in 3D', area, 0.25_rk, 1.0e-13_rk)
    call check_close('half overlap in 3D: centroid moves with the body', norm2(centroid &
        - (matmul(rotation, [0.5_rk, 1.0_rk / 6.0_rk, 0.0_rk]) + shift)), 0.0_rk, 0.0_rk, &
        atol=1.0e-12_rk)
  end subroutine test_overlap_analytic

  !> Degenerate and sliver triangles: zero or the tiny exact area, never NaN.
  subroutine test_overlap_degenerate()
    real(rk), parameter :: z(3) = [0.0_rk, 0.0_rk, 1.0_rk]
    real(rk) :: a(3, 3), b(3, 3), area, centroid(3), h
    logical :: finite

    finite = .true.
    a = triangle(0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk, 1.0_rk)
    b = triangle(0.0_rk, 0.0_rk, 0.5_rk, 0.5_rk, 0.2_rk, 0.2_rk)
    call triangle_overlap(a, b, z, area, centroid)
    finite = finite .and. .not. (ieee_is_nan(area) .or. any(ieee_is_nan(centroid)))
    call check_close('collinear b: 0', area, 0.0_rk, 0.0_rk, atol=tiny(1.0_rk))
    call triangle_overlap(b, a, z, area, centroid)
    finite = finite .and. .not. (ieee_is_nan(area) .or. any(ieee_is_nan(centroid)))
    call check_close('collinear a: 0', area, 0.0_rk, 0.0_rk, atol=tiny(1.0_rk))
    b = triangle(0.2_rk, 0.2_rk, 0.2_rk, 0.2_rk, 0.2_rk, 0.2_rk)
    call triangle_overlap(a, b, z, area, centroid)
    finite = finite .and. .not. (ieee_is_nan(area) .or. any(ieee_is_nan(centroid)))
    call check_close('b a single point: 0', area, 0.0_rk, 0.0_rk, atol=tiny(1.0_rk))
    call triangle_overlap(a, a, [0.0_rk, 0.0_rk, 0.0_rk], area, centroid)
    finite = finite .and. .not. (ieee_is_nan(area) .or. any(ieee_is_nan(centroid)))
    call check_close('zero normal: 0', area, 0.0_rk, 0.0_rk, atol=tiny(1.0_rk))
    b(:, 1) = [0.1_rk, 0.0_rk, 0.0_rk]
    b(:, 2) = [0.6_rk, 0.0_rk, 0.0_rk]
    b(:, 3) = [0.3_rk, 0.0_rk, 0.7_rk]
    call triangle_overlap(a, b, z, area, centroid)
    finite = finite .and. .not. (ieee_is_nan(area) .or. any(ieee_is_nan(centroid)))
    call check_close('b edge-on to the plane: 0', area, 0.0_rk, 0.0_rk, atol=4 * eps)

    h = 2.0e-9_rk
    b = triangle(0.1_rk, 0.1_rk, 0.6_rk, 0.1_rk, 0.35_rk, 0.1_rk + h)
    call triangle_overlap(a, b, z, area, centroid)
    finite = finite .and. .not. (ieee_is_nan(area) .or. any(ieee_is_nan(centroid)))
    call check_close('sliver inside a: its area 0.25 h', area, 0.25_rk * h, 1.0e-6_rk)
    call check_close('sliver inside a: centroid', &
        norm2(centroid - [0.35_rk, 0.1_rk + h / 3.0_rk, 0.0_rk]), 0.0_rk, 0.0_rk, &
        atol=1.0e-8_rk)
    call check_close('a clipped by the sliver: 0.25 h', triangle_overlap_area(b, a, z), &
        0.25_rk * h, 1.0e-6_rk)
    ! Sliver of height h across the hypotenuse: area h int_0^0.8 (1 - |x - 0.5|) dx.
    h = 1.0e-9_rk
    b = triangle(-0.5_rk, 0.2_rk, 1.5_rk, 0.2_rk, 0.5_rk, 0.2_rk + h)
    call triangle_overlap(a, b, z, area, centroid)
    finite = finite .and. .not. (ieee_is_nan(area) .or. any(ieee_is_nan(centroid)))
    call check_close('sliver across two edges of a: 0.63 h', area, 0.63_rk * h, 1.0e-6_rk)
    call triangle_overlap(b, a, z, area, centroid)
    finite = finite .and. .not. (ieee_is_nan(area) .or. any(ieee_is_nan(centroid)))
    call check_close('a clipped by that sliver: 0.63 h', area, 0.63_rk * h, 1.0e-6_rk)
    call check_true('degenerate and sliver cases: no NaN', finite)
  end subroutine test_overlap_degenerate

  !> Projection: a triangle tilted by theta out of the plane shrinks by |cos theta|.
  subroutine test_overlap_projection()
    real(rk), parameter :: z(3) = [0.0_rk, 0.0_rk, 1.0_rk]
    real(rk), parameter :: angles(5) = [0.3_rk, 1.0_rk, 1.4_rk, 2.5_rk, 3.0_rk]
    real(rk) :: a(3, 3), b(3, 3), big(3, 3), tilt(3, 3), centre(3), normal(3), theta, area
    real(rk) :: rotation(3, 3), shift(3)
    integer :: i
    character(len=80) :: name

    big = triangle(-1.0_rk, -1.0_rk, 3.0_rk, -1.0_rk, -1.0_rk, 3.0_rk)
    a = triangle(0.0_rk, 0.0_rk, 1.0_rk, 0.0_rk, 0.0_rk, 1.0_rk)
    centre = sum(a, dim=2) / 3.0_rk
    do i = 1, size(angles)
      theta = angles(i)
      tilt = axis_rotation([1.0_rk, 0.0_rk, 0.0_rk], theta)
      ! Tilt about the x axis through a's centroid: the shadow is inside big.
      b = matmul(tilt, translated(a, -centre))
      b = translated(b, centre)
      write(name, '(a,f4.2,a)') 'tilted by ', theta, ': overlap with big = 0.5 |cos|'
      area = triangle_overlap_area(big, b, z)
      call check_close(trim(name), area, 0.5_rk * abs(cos(theta)), 16 * eps)
      ! Tilt about a's edge on the x axis: the shadow is a scaled by cos in y.
      b = matmul(tilt, a)
      ! Folded beyond pi/2 the shadow falls on the other side of the edge: zero.
      write(name, '(a,f4.2,a)') 'tilted about the shared edge by ', theta, &
          ': 0.5 max(cos, 0)'
      call check_close(trim(name), triangle_overlap_area(a, b, triangle_unit_normal(a)), &
          0.5_rk * max(cos(theta), 0.0_rk), 16 * eps, atol=4 * eps)
    end do
    ! A common plane between the two (DLM): both shadows shrink by cos(theta/2).
    theta = 0.8_rk
    b = matmul(axis_rotation([1.0_rk, 0.0_rk, 0.0_rk], theta), a)
    normal = triangle_unit_normal(a) + triangle_unit_normal(b)
    normal = normal / norm2(normal)
    call check_close('common plane halfway: 0.5 cos(theta/2)', &
        triangle_overlap_area(a, b, normal), 0.5_rk * cos(0.5_rk * theta), 16 * eps)
    call check_close('common plane halfway, roles swapped', &
        triangle_overlap_area(b, a, normal), 0.5_rk * cos(0.5_rk * theta), 16 * eps)
    rotation = random_rotation()
    shift = 10.0_rk * (random_vector() - 0.5_rk)
    call check_close('common plane halfway, moved rigidly in 3D', triangle_overlap_area( &
        moved(a, rotation, shift), moved(b, rotation, shift), matmul(rotation, normal)), &
        0.5_rk * cos(0.5_rk * theta), 64 * eps)
  end subroutine test_overlap_projection

  !> Random pairs in random planes against an independent exact reference, the swapped
  !> roles, reversed normal, out-of-plane offsets, rigid motions and scanline estimates.
  subroutine test_overlap_random()
    integer, parameter :: pairs = 4000, scan_pairs = 400, scan_columns = 4000
    real(rk) :: a2(2, 3), b2(2, 3), a(3, 3), b(3, 3), frame(3, 3), origin(3), normal(3)
    real(rk) :: rotation(3, 3), shift(3), offsets(3), scale, area, swapped, reference
    real(rk) :: centroid(3), reference_centroid(2), area_a, area_b, size_ab, value
    real(rk) :: err_reference, err_swapped, err_normal, err_offset, err_moved
    real(rk) :: err_centroid, err_union, err_inter, inter_estimate, union_estimate
    integer :: pair, nonzero, scanned, partial
    logical :: finite

    err_reference = 0.0_rk
    err_swapped = 0.0_rk
    err_normal = 0.0_rk
    err_offset = 0.0_rk
    err_moved = 0.0_rk
    err_centroid = 0.0_rk
    err_union = 0.0_rk
    err_inter = 0.0_rk
    nonzero = 0
    partial = 0
    scanned = 0
    finite = .true.
    do pair = 1, pairs
      frame = random_rotation()
      origin = 20.0_rk * (random_vector() - 0.5_rk)
      normal = frame(:, 3)
      call random_number(a2)
      call random_number(b2)
      ! Vary the relative size so that nested pairs occur too.
      if (mod(pair, 3) == 0) then
        scale = 0.05_rk + 0.5_rk * random_real()
        b2 = scale * b2 + 0.5_rk * (1.0_rk - scale)
      end if
      a = embed(a2, frame, origin)
      b = embed(b2, frame, origin)
      area_a = abs(area2d(a2))
      area_b = abs(area2d(b2))
      size_ab = max(area_a, area_b)
      call reference_overlap(a2, b2, reference, reference_centroid)
      call triangle_overlap(a, b, normal, area, centroid)
      finite = finite .and. .not. (ieee_is_nan(area) .or. any(ieee_is_nan(centroid)))
      if (area > 0.0_rk) nonzero = nonzero + 1
      if (reference > 1.0e-3_rk * size_ab .and. reference < 0.999_rk * min(area_a, area_b)) &
          partial = partial + 1
      err_reference = max(err_reference, abs(area - reference) / size_ab)
      swapped = triangle_overlap_area(b, a, normal)
      err_swapped = max(err_swapped, abs(area - swapped) / size_ab)
      err_normal = max(err_normal, abs(area - triangle_overlap_area(a, b, -normal)) / size_ab)
      ! Offsets of b along the normal do not change its shadow.
      call random_number(offsets)
      value = triangle_overlap_area(a, b + spread(normal, 2, 3) &
          * spread(offsets - 0.5_rk, 1, 3), normal)
      err_offset = max(err_offset, abs(area - value) / size_ab)
      rotation = random_rotation()
      shift = 50.0_rk * (random_vector() - 0.5_rk)
      value = triangle_overlap_area(moved(a, rotation, shift), moved(b, rotation, shift), &
          matmul(rotation, normal))
      err_moved = max(err_moved, abs(area - value) / size_ab)
      if (reference > 1.0e-3_rk * size_ab) then
        err_centroid = max(err_centroid, norm2(centroid - (origin &
            + reference_centroid(1) * frame(:, 1) + reference_centroid(2) * frame(:, 2))))
      end if
      if (scanned < scan_pairs .and. reference > 0.05_rk * size_ab) then
        scanned = scanned + 1
        call scanline_estimate(a2, b2, scan_columns, inter_estimate, union_estimate)
        err_inter = max(err_inter, abs(inter_estimate - area) / (area_a + area_b - area))
        err_union = max(err_union, abs(union_estimate - (area_a + area_b - area)) &
            / (area_a + area_b - area))
      end if
    end do
    write(output_unit, '(a,i0,a,i0,a,i0,a)') 'info random pairs: ', pairs, ' (', nonzero, &
        ' overlapping, ', partial, ' partially)'
    call check_true('random pairs: enough partial overlaps', partial > pairs / 4)
    call check_true('random pairs: no NaN', finite)
    call check_close('random pairs: vs exact reference (max rel diff)', err_reference, 0.0_rk, &
        0.0_rk, atol=1.0e-12_rk)
    call check_close('random pairs: overlap(a,b) = overlap(b,a)', err_swapped, 0.0_rk, &
        0.0_rk, atol=1.0e-12_rk)
    call check_close('random pairs: normal reversed', err_normal, 0.0_rk, 0.0_rk, &
        atol=1.0e-12_rk)
    call check_close('random pairs: b offset along the normal', err_offset, 0.0_rk, 0.0_rk, &
        atol=1.0e-12_rk)
    call check_close('random pairs: rotated and translated in 3D', err_moved, 0.0_rk, &
        0.0_rk, atol=1.0e-12_rk)
    call check_close('random pairs: centroid vs reference (max distance)', err_centroid, &
        0.0_rk, 0.0_rk, atol=1.0e-10_rk)
    ! Midpoint-rule error: h^2/8 times the slope jumps at the kinks (steep edges).
    call check_close('scanlines, 400 overlapping pairs: intersection (rel to union)', &
        err_inter, 0.0_rk, 0.0_rk, atol=1.0e-3_rk)
    call check_close('scanlines, 400 overlapping pairs: union = A + B - overlap (rel)', &
        err_union, 0.0_rk, 0.0_rk, atol=1.0e-3_rk)
  end subroutine test_overlap_random

  !> Pairs built from one triangle with exactly or nearly shared vertices (the
  !> matching-mesh cases of contact), in random 3D frames: within bounds, never NaN.
  subroutine test_overlap_near_degenerate()
    integer, parameter :: pairs = 2000
    real(rk), parameter :: noise = 1.0e-13_rk
    real(rk) :: a2(2, 3), b2(2, 3), jitter(2, 3), frame(3, 3), origin(3), a(3, 3), b(3, 3)
    real(rk) :: area, centroid(3), area_a, err_same, err_opposite, err_bound
    integer :: pair, kind
    logical :: finite

    err_same = 0.0_rk
    err_opposite = 0.0_rk
    err_bound = 0.0_rk
    finite = .true.
    do pair = 1, pairs
      frame = random_rotation()
      origin = 1000.0_rk * (random_vector() - 0.5_rk)
      call random_number(a2)
      area_a = abs(area2d(a2))
      if (area_a < 1.0e-2_rk) cycle
      call random_number(jitter)
      jitter = noise * (jitter - 0.5_rk)
      kind = mod(pair, 4)
      select case (kind)
      case (0)
        ! The same triangle, reversed (facing surfaces), vertices jittered.
        b2 = a2(:, [3, 2, 1]) + jitter
      case (1)
        ! Reflected through its first edge: a shared edge, opposite sides.
        b2 = a2
        b2(:, 3) = a2(:, 1) + a2(:, 2) - a2(:, 3)
        b2 = b2 + jitter
      case (2)
        ! Point-reflected through vertex 1: touching at one vertex.
        b2 = 2.0_rk * spread(a2(:, 1), 2, 3) - a2
        b2 = b2 + jitter
      case default
        ! Sharing vertex 1, the rest random: any overlap within bounds.
        call random_number(b2)
        b2(:, 1) = a2(:, 1) + jitter(:, 1)
      end select
      a = embed(a2, frame, origin)
      b = embed(b2, frame, origin)
      call triangle_overlap(a, b, frame(:, 3), area, centroid)
      finite = finite .and. .not. (ieee_is_nan(area) .or. any(ieee_is_nan(centroid)))
      select case (kind)
      case (0)
        err_same = max(err_same, abs(area - area_a) / area_a)
      case (1, 2)
        err_opposite = max(err_opposite, area / area_a)
      case default
        err_bound = max(err_bound, (area - min(area_a, abs(area2d(b2)))) / area_a)
      end select
    end do
    call check_true('near-coincident pairs: no NaN', finite)
    ! The jitter moves the exact overlap by up to about perimeter * noise / area.
    call check_close('coincident facing facets (jittered 1e-13): full area', err_same, &
        0.0_rk, 0.0_rk, atol=1.0e-9_rk)
    call check_close('shared edge or vertex, jittered 1e-13, far from origin: ~0', &
        err_opposite, 0.0_rk, 0.0_rk, atol=1.0e-9_rk)
    call check_true('shared vertex: overlap <= smaller area', err_bound <= 1.0e-12_rk)
  end subroutine test_overlap_near_degenerate

  !> Partition of unity (DAM): the master facets of a patch tile the plane, so the
  !> overlaps of a slave facet with all of them sum to the slave facet's area, with
  !> the slave surface facing the master (reversed), offset and tilted.
  subroutine test_overlap_partition()
    integer, parameter :: cells = 3, trials = 20
    real(rk) :: nodes(3, 0:cells, 0:cells), quad(3, 4), slave(3, 4), tilt(3, 3)
    real(rk) :: master_facets(3, 3, SEGMENT_FACET_COUNT, cells * cells)
    real(rk) :: slave_facets(3, 3, SEGMENT_FACET_COUNT), normal(3), total, facet_area
    real(rk) :: err_facet, err_node, slave_area(4), node_sum(4), jitter(2), patch_area
    integer :: i, j, trial, f, g, m

    err_facet = 0.0_rk
    err_node = 0.0_rk
    do trial = 1, trials
      ! A planar 3 x 3 master patch in z = 0 with jittered interior nodes.
      do j = 0, cells
        do i = 0, cells
          nodes(:, i, j) = [real(i, rk), real(j, rk), 0.0_rk]
          if (i > 0 .and. i < cells .and. j > 0 .and. j < cells) then
            call random_number(jitter)
            nodes(1:2, i, j) = nodes(1:2, i, j) + 0.4_rk * (jitter - 0.5_rk)
          end if
        end do
      end do
      patch_area = 0.0_rk
      m = 0
      do j = 1, cells
        do i = 1, cells
          m = m + 1
          quad = reshape([nodes(:, i - 1, j - 1), nodes(:, i, j - 1), nodes(:, i, j), &
              nodes(:, i - 1, j)], [3, 4])
          call segment_facets(quad, master_facets(:, :, :, m))
          patch_area = patch_area + segment_area(quad)
        end do
      end do
      ! A slave segment inside [0.7, 2.3]^2 facing down (clockwise seen from +z),
      ! lifted by a gap and tilted by up to 0.3 rad about an axis through its centre.
      slave = 0.0_rk
      call random_number(slave(1:2, :))
      slave(1:2, :) = 0.7_rk + 1.6_rk * real(reshape([0, 0, 0, 1, 1, 1, 1, 0], [2, 4]), rk) &
          + 0.3_rk * (slave(1:2, :) - 0.5_rk)
      tilt = axis_rotation(random_unit_in_plane(), 0.3_rk * random_real())
      slave = matmul(tilt, slave - 1.5_rk) + 1.5_rk
      slave(3, :) = slave(3, :) + 0.01_rk
      call segment_facets(slave, slave_facets)
      call corner_areas(slave, slave_area)
      node_sum = 0.0_rk
      do f = 1, SEGMENT_FACET_COUNT
        normal = triangle_unit_normal(slave_facets(:, :, f))
        total = 0.0_rk
        do m = 1, cells * cells
          do g = 1, SEGMENT_FACET_COUNT
            total = total + triangle_overlap_area(slave_facets(:, :, f), &
                master_facets(:, :, g, m), normal)
          end do
        end do
        facet_area = norm2(triangle_vector_area(slave_facets(:, :, f)))
        err_facet = max(err_facet, abs(total - facet_area) / facet_area)
        node_sum(FACET_CORNER(f)) = node_sum(FACET_CORNER(f)) + total
      end do
      err_node = max(err_node, maxval(abs(node_sum - slave_area) / slave_area))
    end do
    call check_close('master patch area = 9', patch_area, 9.0_rk, 64 * eps)
    call check_close('slave facet covered by master facets: overlaps sum to its area', &
        err_facet, 0.0_rk, 0.0_rk, atol=1.0e-13_rk)
    call check_close('slave node covered by master facets: overlaps sum to sp(n)', &
        err_node, 0.0_rk, 0.0_rk, atol=1.0e-13_rk)
  end subroutine test_overlap_partition

  ! ---- Independent references -------------------------------------------------------

  !> Exact overlap of two 2D triangles by another method: collect the vertices of
  !> each inside the other and all edge-edge intersections, sort them by angle about
  !> their mean (the overlap is convex) and apply the shoelace formula.
  subroutine reference_overlap(a, b, area, centroid)
    real(rk), intent(in) :: a(2, 3), b(2, 3)
    real(rk), intent(out) :: area, centroid(2)
    real(rk) :: points(2, 15), angle(15), mean(2), r(2), w(2), q(2), denominator, s, u
    real(rk) :: cross_term, twice_area, moment(2), swap(2), swap_angle
    integer :: n, i, j, k, l

    n = 0
    do i = 1, 3
      if (inside(a(:, i), b)) call add_point(points, n, a(:, i))
      if (inside(b(:, i), a)) call add_point(points, n, b(:, i))
    end do
    do i = 1, 3
      r = a(:, mod(i, 3) + 1) - a(:, i)
      do j = 1, 3
        w = b(:, mod(j, 3) + 1) - b(:, j)
        q = b(:, j) - a(:, i)
        denominator = r(1) * w(2) - r(2) * w(1)
        if (abs(denominator) > 0.0_rk) then
          s = (q(1) * w(2) - q(2) * w(1)) / denominator
          u = (q(1) * r(2) - q(2) * r(1)) / denominator
          if (s >= 0.0_rk .and. s <= 1.0_rk .and. u >= 0.0_rk .and. u <= 1.0_rk) &
              call add_point(points, n, a(:, i) + s * r)
        end if
      end do
    end do
    area = 0.0_rk
    centroid = 0.0_rk
    if (n < 3) return
    mean = sum(points(:, 1:n), dim=2) / real(n, rk)
    do i = 1, n
      angle(i) = atan2(points(2, i) - mean(2), points(1, i) - mean(1))
    end do
    ! Insertion sort by angle.
    do k = 2, n
      l = k
      do while (l > 1)
        if (angle(l - 1) <= angle(l)) exit
        swap = points(:, l)
        points(:, l) = points(:, l - 1)
        points(:, l - 1) = swap
        swap_angle = angle(l)
        angle(l) = angle(l - 1)
        angle(l - 1) = swap_angle
        l = l - 1
      end do
    end do
    twice_area = 0.0_rk
    moment = 0.0_rk
    do i = 1, n
      r = points(:, i) - mean
      w = points(:, mod(i, n) + 1) - mean
      cross_term = r(1) * w(2) - r(2) * w(1)
      twice_area = twice_area + cross_term
      moment = moment + cross_term * (r + w)
    end do
    area = 0.5_rk * twice_area
    if (twice_area > 0.0_rk) centroid = mean + moment / (3.0_rk * twice_area)
  end subroutine reference_overlap

  subroutine add_point(points, n, point)
    real(rk), intent(inout) :: points(:, :)
    integer, intent(inout) :: n
    real(rk), intent(in) :: point(2)
    n = n + 1
    points(:, n) = point
  end subroutine add_point

  !> Point in a 2D triangle of either orientation, boundary included.
  pure function inside(p, t) result(is_inside)
    real(rk), intent(in) :: p(2), t(2, 3)
    logical :: is_inside
    real(rk) :: d(3)
    integer :: i, j
    do i = 1, 3
      j = mod(i, 3) + 1
      d(i) = (t(1, j) - t(1, i)) * (p(2) - t(2, i)) - (t(2, j) - t(2, i)) * (p(1) - t(1, i))
    end do
    is_inside = all(d >= 0.0_rk) .or. all(d <= 0.0_rk)
  end function inside

  !> Scanline estimates of |A and B| and |A or B|: at the midpoints of n columns over
  !> their x range, the exact vertical extent of each triangle gives the lengths of
  !> the intersection and union of the two intervals; the midpoint rule in x is then
  !> second order (the lengths are piecewise linear in x).
  subroutine scanline_estimate(a, b, n, intersection, union)
    real(rk), intent(in) :: a(2, 3), b(2, 3)
    integer, intent(in) :: n
    real(rk), intent(out) :: intersection, union
    real(rk) :: low, high, h, x, interval_a(2), interval_b(2), common
    integer :: i
    low = min(minval(a(1, :)), minval(b(1, :)))
    high = max(maxval(a(1, :)), maxval(b(1, :)))
    h = (high - low) / n
    intersection = 0.0_rk
    union = 0.0_rk
    do i = 1, n
      x = low + (i - 0.5_rk) * h
      interval_a = vertical_extent(a, x)
      interval_b = vertical_extent(b, x)
      common = max(0.0_rk, min(interval_a(2), interval_b(2)) - max(interval_a(1), interval_b(1)))
      intersection = intersection + h * common
      union = union + h * (interval_a(2) - interval_a(1) + interval_b(2) - interval_b(1) - common)
    end do
  end subroutine scanline_estimate

  !> [ymin, ymax] of a 2D triangle on the vertical line at x; [0, 0] if it misses it.
  pure function vertical_extent(t, x) result(interval)
    real(rk), intent(in) :: t(2, 3), x
    real(rk) :: interval(2), y, s
    integer :: i, j
    logical :: hit
    interval = [huge(1.0_rk), -huge(1.0_rk)]
    hit = .false.
    do i = 1, 3
      j = mod(i, 3) + 1
      if ((t(1, i) - x) * (t(1, j) - x) < 0.0_rk) then
        s = (x - t(1, i)) / (t(1, j) - t(1, i))
        y = t(2, i) + s * (t(2, j) - t(2, i))
        interval = [min(interval(1), y), max(interval(2), y)]
        hit = .true.
      end if
    end do
    if (.not. hit) interval = 0.0_rk
  end function vertical_extent

  !> Area of a bilinear patch by tensor Gauss-Legendre quadrature of |x_s x x_t|.
  function bilinear_area(p) result(area)
    real(rk), intent(in) :: p(3, 4)
    real(rk) :: area
    real(rk) :: xs(3), xt(3), s, t
    integer :: i, j
    area = 0.0_rk
    do j = 1, GAUSS_ORDER
      t = gauss_x(j)
      do i = 1, GAUSS_ORDER
        s = gauss_x(i)
        xs = (1.0_rk - t) * (p(:, 2) - p(:, 1)) + t * (p(:, 3) - p(:, 4))
        xt = (1.0_rk - s) * (p(:, 4) - p(:, 1)) + s * (p(:, 3) - p(:, 2))
        area = area + gauss_w(i) * gauss_w(j) * norm2(cross3(xs, xt))
      end do
    end do
  end function bilinear_area

  !> Gauss-Legendre nodes and weights on [0, 1] (Newton on P_n).
  subroutine gauss_legendre(n, x, w)
    integer, intent(in) :: n
    real(rk), intent(out) :: x(n), w(n)
    real(rk) :: z, p0, p1, p2, dp
    integer :: i, k, iteration
    do i = 1, n
      z = cos(pi * (i - 0.25_rk) / (n + 0.5_rk))
      do iteration = 1, 100
        p0 = 1.0_rk
        p1 = z
        do k = 2, n
          p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k
          p0 = p1
          p1 = p2
        end do
        dp = n * (z * p1 - p0) / (z**2 - 1.0_rk)
        if (abs(p1 / dp) < 4 * eps) exit
        z = z - p1 / dp
      end do
      x(i) = 0.5_rk * (1.0_rk - z)
      w(i) = 1.0_rk / ((1.0_rk - z**2) * dp**2)
    end do
  end subroutine gauss_legendre

  ! ---- Construction helpers -----------------------------------------------------------

  !> Unit square in z = 0 with corner heights +h, -h, +h, -h.
  function square(h) result(p)
    real(rk), intent(in) :: h
    real(rk) :: p(3, 4)
    p = reshape([0.0_rk, 0.0_rk, h, 1.0_rk, 0.0_rk, -h, 1.0_rk, 1.0_rk, h, &
        0.0_rk, 1.0_rk, -h], [3, 4])
  end function square

  !> Convex quad on a random ellipse in a random plane, corners counter-clockwise,
  !> warped by +-warp * size along the plane normal.
  function random_convex_quad(warp) result(p)
    real(rk), intent(in) :: warp
    real(rk) :: p(3, 4)
    real(rk) :: frame(3, 3), origin(3), axes(2), theta, size
    integer :: k
    frame = random_rotation()
    origin = 20.0_rk * (random_vector() - 0.5_rk)
    axes = [0.2_rk + 2.0_rk * random_real(), 0.2_rk + 2.0_rk * random_real()]
    size = sqrt(axes(1) * axes(2))
    do k = 1, 4
      theta = 0.5_rk * pi * (k - 1) + 1.2_rk * (random_real() - 0.5_rk)
      p(:, k) = origin + axes(1) * cos(theta) * frame(:, 1) &
          + axes(2) * sin(theta) * frame(:, 2) + warp * size * (-1.0_rk)**(k - 1) * frame(:, 3)
    end do
  end function random_convex_quad

  function triangle(x1, y1, x2, y2, x3, y3) result(t)
    real(rk), intent(in) :: x1, y1, x2, y2, x3, y3
    real(rk) :: t(3, 3)
    t = reshape([x1, y1, 0.0_rk, x2, y2, 0.0_rk, x3, y3, 0.0_rk], [3, 3])
  end function triangle

  function translated(t, shift) result(moved_t)
    real(rk), intent(in) :: t(3, 3), shift(3)
    real(rk) :: moved_t(3, 3)
    moved_t = t + spread(shift, 2, 3)
  end function translated

  function moved(t, rotation, shift) result(moved_t)
    real(rk), intent(in) :: t(3, 3), rotation(3, 3), shift(3)
    real(rk) :: moved_t(3, 3)
    moved_t = matmul(rotation, t) + spread(shift, 2, 3)
  end function moved

  !> 3D triangle from 2D coordinates in the plane of frame(:, 1:2) through origin.
  function embed(t2, frame, origin) result(t)
    real(rk), intent(in) :: t2(2, 3), frame(3, 3), origin(3)
    real(rk) :: t(3, 3)
    integer :: k
    do k = 1, 3
      t(:, k) = origin + t2(1, k) * frame(:, 1) + t2(2, k) * frame(:, 2)
    end do
  end function embed

  pure function area2d(t) result(area)
    real(rk), intent(in) :: t(2, 3)
    real(rk) :: area
    area = 0.5_rk * ((t(1, 2) - t(1, 1)) * (t(2, 3) - t(2, 1)) &
        - (t(2, 2) - t(2, 1)) * (t(1, 3) - t(1, 1)))
  end function area2d

  !> Proper rotation from a random unit quaternion.
  function random_rotation() result(r)
    real(rk) :: r(3, 3), q(4)
    call random_number(q)
    q = q - 0.5_rk
    q = q / norm2(q)
    r(1, :) = [1 - 2 * (q(3)**2 + q(4)**2), 2 * (q(2) * q(3) - q(1) * q(4)), &
        2 * (q(2) * q(4) + q(1) * q(3))]
    r(2, :) = [2 * (q(2) * q(3) + q(1) * q(4)), 1 - 2 * (q(2)**2 + q(4)**2), &
        2 * (q(3) * q(4) - q(1) * q(2))]
    r(3, :) = [2 * (q(2) * q(4) - q(1) * q(3)), 2 * (q(3) * q(4) + q(1) * q(2)), &
        1 - 2 * (q(2)**2 + q(3)**2)]
  end function random_rotation

  !> Rotation by angle about a unit axis (Rodrigues).
  pure function axis_rotation(axis, angle) result(r)
    real(rk), intent(in) :: axis(3), angle
    real(rk) :: r(3, 3), k(3, 3)
    integer :: i
    k = reshape([0.0_rk, axis(3), -axis(2), -axis(3), 0.0_rk, axis(1), axis(2), -axis(1), &
        0.0_rk], [3, 3])
    r = sin(angle) * k + (1.0_rk - cos(angle)) * matmul(k, k)
    do i = 1, 3
      r(i, i) = r(i, i) + 1.0_rk
    end do
  end function axis_rotation

  !> Random unit vector in the plane z = 0.
  function random_unit_in_plane() result(v)
    real(rk) :: v(3), angle
    angle = 2.0_rk * pi * random_real()
    v = [cos(angle), sin(angle), 0.0_rk]
  end function random_unit_in_plane

  function random_vector() result(v)
    real(rk) :: v(3)
    call random_number(v)
  end function random_vector

  function random_real() result(r)
    real(rk) :: r
    call random_number(r)
  end function random_real

  pure function cross3(a, b) result(c)
    real(rk), intent(in) :: a(3), b(3)
    real(rk) :: c(3)
    c = [a(2) * b(3) - a(3) * b(2), a(3) * b(1) - a(1) * b(3), a(1) * b(2) - a(2) * b(1)]
  end function cross3

end program test_contact_geometry
