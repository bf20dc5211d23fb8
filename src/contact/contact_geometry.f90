!> Contact geometry kernels (plain arrays, no MPI, no I/O): segment facets, nodal
!> (dual-cell) areas, and the overlap of two triangles projected onto a plane.
!>
!> Facets. A segment with corners p(:, 1:4), counter-clockwise about its outward
!> normal, is split into 8 flat triangles around its centre c = (p1 + p2 + p3 + p4)/4.
!> With m(k) = (p(k) + p(k+1))/2 the midpoint of edge k -> k+1 (indices mod 4), corner
!> k owns facet 2k-1 = (p(k), m(k), c) and facet 2k = (p(k), c, m(k-1)). Both are
!> counter-clockwise about the outward normal, like the segment; for a convex planar
!> segment every facet has a positive area along the normal.
!>
!> Warped segments. When the four corners are not coplanar the facets are still the
!> flat triangles through these 9 points. All 9 lie on the bilinear surface (its edges
!> are straight and c = x(0, 0)), but the 8-triangle surface is not the bilinear one.
!> Contact defines the segment area as the area of the 8-triangle surface:
!> segment_area(p) = sum of the 8 facet areas, so "facets sum to the segment area" and
!> "corner areas sum to the segment area" hold to round-off by construction. It
!> differs from the area of the bilinear surface by O(h^2), h the warp (distance of the
!> corners from their mean plane over the segment size): for the unit square with
!> corner heights +h, -h, +h, -h it is sqrt(1 + 4 h^2) = 1 + 2 h^2 + O(h^4), against
!> 1 + 4 h^2/3 + O(h^4) for the bilinear surface. The vector sum of the facet areas
!> depends only on the boundary and is exactly the segment's vector area
!> (quad_vector_area), so norm2(quad_vector_area(p)) <= segment_area(p), with equality
!> for a planar segment.
!>
!> Overlaps. Both triangles are projected orthogonally onto the plane through the
!> centroid of the first one with the given unit normal, each projected triangle is
!> made counter-clockwise, the second is clipped by the three edges of the first
!> (Sutherland-Hodgman) and the area of the clipped polygon is the shoelace sum; its
!> centroid is returned too (DLM measures the gap there). Swapping the triangles
!> changes the result only by round-off when both lie in a plane normal to `normal`.
!> Degenerate input (a zero-area projected triangle, a zero normal) gives zero.
module contact_geometry
  use core_kinds, only: rk, ik
  use mesh_geometry, only: quad_vector_area
  implicit none
  private
  public :: segment_facets, segment_area, corner_areas, quad_unit_normal
  public :: triangle_vector_area, triangle_unit_normal
  public :: triangle_overlap, triangle_overlap_area, triangle_overlap_2d
  public :: SEGMENT_FACET_COUNT, FACET_CORNER, tangent_basis
  public :: segment_box, project_facets, facet_box, boxes_meet, covered, plane_offset, &
      bilinear_shape

  !> Number of facets of one segment.
  integer, parameter :: SEGMENT_FACET_COUNT = 8
  !> Local corner (1..4) owning each facet of a segment.
  integer, parameter :: FACET_CORNER(SEGMENT_FACET_COUNT) = [1, 1, 2, 2, 3, 3, 4, 4]
  !> Room for the polygon clipped by three edges: each clip at most doubles the count
  !> (a convex polygon gains one vertex; the bound also covers round-off).
  integer, parameter :: MAX_VERTICES = 24
  !> Room a caller gives triangle_overlap_2d for the overlap polygon.
  integer, parameter, public :: OVERLAP_VERTICES = MAX_VERTICES

contains

  pure function cross(a, b) result(c)
    real(rk), intent(in) :: a(3), b(3)
    real(rk) :: c(3)
    c(1) = a(2) * b(3) - a(3) * b(2)
    c(2) = a(3) * b(1) - a(1) * b(3)
    c(3) = a(1) * b(2) - a(2) * b(1)
  end function cross

  !> The 8 facets of a segment, facets 2k-1 and 2k belonging to corner k (see above).
  pure subroutine segment_facets(p, facets)
    real(rk), intent(in) :: p(3, 4) !< corners, counter-clockwise about the outward normal
    real(rk), intent(out) :: facets(3, 3, SEGMENT_FACET_COUNT) !< (xyz, vertex, facet)
    real(rk) :: centre(3), midpoint(3, 4)
    integer :: k

    centre = 0.25_rk * (p(:, 1) + p(:, 2) + p(:, 3) + p(:, 4))
    do k = 1, 4
      midpoint(:, k) = 0.5_rk * (p(:, k) + p(:, mod(k, 4) + 1))
    end do
    do k = 1, 4
      facets(:, 1, 2 * k - 1) = p(:, k)
      facets(:, 2, 2 * k - 1) = midpoint(:, k)
      facets(:, 3, 2 * k - 1) = centre
      facets(:, 1, 2 * k) = p(:, k)
      facets(:, 2, 2 * k) = centre
      facets(:, 3, 2 * k) = midpoint(:, mod(k + 2, 4) + 1)
    end do
  end subroutine segment_facets

  !> Dual-cell area of each corner on this segment: the sum of its two facet areas.
  pure subroutine corner_areas(p, area)
    real(rk), intent(in) :: p(3, 4) !< corners, counter-clockwise about the outward normal
    real(rk), intent(out) :: area(4) !< area owned by each corner; sum = segment_area(p)
    real(rk) :: facets(3, 3, SEGMENT_FACET_COUNT)
    integer :: k

    call segment_facets(p, facets)
    do k = 1, 4
      area(k) = norm2(triangle_vector_area(facets(:, :, 2 * k - 1))) &
          + norm2(triangle_vector_area(facets(:, :, 2 * k)))
    end do
  end subroutine corner_areas

  !> Segment area used by contact: the sum of the 8 facet areas (see the module notes
  !> for warped segments).
  pure function segment_area(p) result(area)
    real(rk), intent(in) :: p(3, 4) !< corners, counter-clockwise about the outward normal
    real(rk) :: area
    real(rk) :: corner(4)

    call corner_areas(p, corner)
    area = ((corner(1) + corner(2)) + corner(3)) + corner(4)
  end function segment_area

  !> Unit outward normal of a segment, from its exact vector area; zero if that is zero.
  pure function quad_unit_normal(p) result(normal)
    real(rk), intent(in) :: p(3, 4) !< corners, counter-clockwise about the outward normal
    real(rk) :: normal(3)
    real(rk) :: length

    normal = quad_vector_area(p)
    length = norm2(normal)
    if (length > 0.0_rk) then
      normal = normal / length
    else
      normal = 0.0_rk
    end if
  end function quad_unit_normal

  !> Vector area of a triangle t(:, 1:3): half the cross product of two edges.
  pure function triangle_vector_area(t) result(area)
    real(rk), intent(in) :: t(3, 3) !< vertices in columns
    real(rk) :: area(3)
    area = 0.5_rk * cross(t(:, 2) - t(:, 1), t(:, 3) - t(:, 1))
  end function triangle_vector_area

  !> Unit normal of a triangle (right-hand rule on the vertex order); zero if degenerate.
  pure function triangle_unit_normal(t) result(normal)
    real(rk), intent(in) :: t(3, 3) !< vertices in columns
    real(rk) :: normal(3)
    real(rk) :: length

    normal = triangle_vector_area(t)
    length = norm2(normal)
    if (length > 0.0_rk) then
      normal = normal / length
    else
      normal = 0.0_rk
    end if
  end function triangle_unit_normal

  !> Area of the overlap of triangles a and b projected onto the plane through a's
  !> centroid with normal `normal`; either vertex order, zero when degenerate.
  pure function triangle_overlap_area(a, b, normal) result(area)
    real(rk), intent(in) :: a(3, 3) !< first triangle, vertices in columns
    real(rk), intent(in) :: b(3, 3) !< second triangle, vertices in columns
    real(rk), intent(in) :: normal(3) !< plane normal (a's unit normal for DAM)
    real(rk) :: area
    real(rk) :: centroid(3)

    call triangle_overlap(a, b, normal, area, centroid)
  end function triangle_overlap_area

  !> Area and centroid of the overlap of triangles a and b projected onto the plane
  !> through a's centroid with normal `normal`. The centroid lies in that plane; when
  !> the overlap is empty or degenerate it is the mean of the clipped polygon's
  !> vertices, or a's centroid if there are none.
  pure subroutine triangle_overlap(a, b, normal, area, centroid)
    real(rk), intent(in) :: a(3, 3) !< first triangle (the clipper), vertices in columns
    real(rk), intent(in) :: b(3, 3) !< second triangle (clipped), vertices in columns
    real(rk), intent(in) :: normal(3) !< plane normal; normalised here, zero gives zero
    real(rk), intent(out) :: area !< overlap area, >= 0
    real(rk), intent(out) :: centroid(3) !< overlap centroid, in the projection plane
    real(rk) :: origin(3), unit_normal(3), tangent1(3), tangent2(3), length
    real(rk) :: a2(2, 3), b2(2, 3), centre2(2)
    integer :: k

    origin = (a(:, 1) + a(:, 2) + a(:, 3)) / 3.0_rk
    area = 0.0_rk
    centroid = origin
    length = norm2(normal)
    if (.not. (length > 0.0_rk)) return
    unit_normal = normal / length
    call tangent_basis(unit_normal, tangent1, tangent2)
    do k = 1, 3
      a2(1, k) = dot_product(a(:, k) - origin, tangent1)
      a2(2, k) = dot_product(a(:, k) - origin, tangent2)
      b2(1, k) = dot_product(b(:, k) - origin, tangent1)
      b2(2, k) = dot_product(b(:, k) - origin, tangent2)
    end do
    call triangle_overlap_2d(a2, b2, area, centre2)
    centroid = origin + centre2(1) * tangent1 + centre2(2) * tangent2
  end subroutine triangle_overlap

  !> Area and centroid of the overlap of two triangles already projected on a
  !> plane (2D coordinates, any orientation). Zero area and the centroid (0, 0)
  !> when either triangle is degenerate.
  pure subroutine triangle_overlap_2d(a2, b2, area, centre2, vertices, nvertex)
    real(rk), intent(in) :: a2(2, 3) !< the clipper
    real(rk), intent(in) :: b2(2, 3) !< the clipped
    real(rk), intent(out) :: area, centre2(2)
    !> the overlap polygon's vertices (2, >= OVERLAP_VERTICES) and their number
    real(rk), intent(out), optional :: vertices(:, :)
    integer, intent(out), optional :: nvertex
    real(rk) :: a(2, 3), b(2, 3), polygon(2, MAX_VERTICES)
    integer :: count
    logical :: valid
    area = 0.0_rk
    centre2 = 0.0_rk
    if (present(nvertex)) nvertex = 0
    a = a2
    b = b2
    call make_counter_clockwise(a, valid)
    if (.not. valid) return
    call make_counter_clockwise(b, valid)
    if (.not. valid) return
    call clip_triangle(b, a, polygon, count)
    call polygon_area_centroid(polygon, count, area, centre2)
    if (present(vertices) .and. present(nvertex)) then
      nvertex = count
      vertices(:, :count) = polygon(:, :count)
    end if
  end subroutine triangle_overlap_2d

  !> Orthonormal tangents with tangent1 x tangent2 = normal (normal of unit length).
  pure subroutine tangent_basis(normal, tangent1, tangent2)
    real(rk), intent(in) :: normal(3)
    real(rk), intent(out) :: tangent1(3), tangent2(3)
    real(rk) :: axis(3)
    integer :: i

    ! Start from the coordinate axis least aligned with the normal.
    i = minloc(abs(normal), dim=1)
    axis = 0.0_rk
    axis(i) = 1.0_rk
    tangent1 = axis - normal(i) * normal
    tangent1 = tangent1 / norm2(tangent1)
    tangent2 = cross(normal, tangent1)
  end subroutine tangent_basis

  !> Reorder a 2D triangle counter-clockwise; false if its signed area is zero.
  pure subroutine make_counter_clockwise(t, valid)
    real(rk), intent(inout) :: t(2, 3)
    logical, intent(out) :: valid
    real(rk) :: twice_area, swap(2)

    twice_area = (t(1, 2) - t(1, 1)) * (t(2, 3) - t(2, 1)) &
        - (t(2, 2) - t(2, 1)) * (t(1, 3) - t(1, 1))
    valid = twice_area > 0.0_rk .or. twice_area < 0.0_rk
    if (twice_area < 0.0_rk) then
      swap = t(:, 2)
      t(:, 2) = t(:, 3)
      t(:, 3) = swap
    end if
  end subroutine make_counter_clockwise

  !> Sutherland-Hodgman: clip triangle `subject` by the three edges of `clipper` (both
  !> counter-clockwise). A point on an edge counts as inside; an edge is cut only
  !> where the signed distances of its ends differ strictly in sign, so no division
  !> by zero can occur.
  pure subroutine clip_triangle(subject, clipper, polygon, count)
    real(rk), intent(in) :: subject(2, 3), clipper(2, 3)
    real(rk), intent(out) :: polygon(2, MAX_VERTICES)
    integer, intent(out) :: count
    real(rk) :: work(2, MAX_VERTICES), distance(MAX_VERTICES), start(2), edge(2), s
    integer :: e, i, j, n

    polygon(:, 1:3) = subject
    count = 3
    do e = 1, 3
      start = clipper(:, e)
      edge = clipper(:, mod(e, 3) + 1) - start
      n = count
      do i = 1, n
        distance(i) = edge(1) * (polygon(2, i) - start(2)) - edge(2) * (polygon(1, i) - start(1))
      end do
      ! Nothing outside this edge: the polygon is unchanged.
      if (all(distance(1:n) >= 0.0_rk)) cycle
      work(:, 1:n) = polygon(:, 1:n)
      count = 0
      do i = 1, n
        j = mod(i, n) + 1
        if (distance(i) >= 0.0_rk) then
          count = count + 1
          polygon(:, count) = work(:, i)
          if (distance(j) < 0.0_rk) then
            s = distance(i) / (distance(i) - distance(j))
            count = count + 1
            polygon(:, count) = work(:, i) + s * (work(:, j) - work(:, i))
          end if
        else if (distance(j) >= 0.0_rk) then
          s = distance(i) / (distance(i) - distance(j))
          count = count + 1
          polygon(:, count) = work(:, i) + s * (work(:, j) - work(:, i))
        end if
      end do
      if (count == 0) return
    end do
  end subroutine clip_triangle

  !> Shoelace area and centroid of a counter-clockwise 2D polygon, relative to the
  !> mean of its vertices; a polygon of (numerically) zero area gets that mean.
  pure subroutine polygon_area_centroid(polygon, count, area, centroid)
    real(rk), intent(in) :: polygon(2, MAX_VERTICES)
    integer, intent(in) :: count
    real(rk), intent(out) :: area, centroid(2)
    real(rk) :: mean(2), u(2), v(2), term, twice_area, moment(2), extent2
    integer :: i

    area = 0.0_rk
    centroid = 0.0_rk
    if (count == 0) return
    mean = sum(polygon(:, 1:count), dim=2) / real(count, rk)
    centroid = mean
    if (count < 3) return
    twice_area = 0.0_rk
    moment = 0.0_rk
    extent2 = 0.0_rk
    do i = 1, count
      u = polygon(:, i) - mean
      v = polygon(:, mod(i, count) + 1) - mean
      term = u(1) * v(2) - u(2) * v(1)
      twice_area = twice_area + term
      moment = moment + term * (u + v)
      extent2 = max(extent2, u(1)**2 + u(2)**2)
    end do
    area = max(0.5_rk * twice_area, 0.0_rk)
    if (twice_area > 64.0_rk * epsilon(1.0_rk) * extent2) then
      centroid = mean + moment / (3.0_rk * twice_area)
    end if
  end subroutine polygon_area_centroid

  !> Bounding box of a segment's corners projected on the plane spanned by
  !> t1, t2 (its facets' centre and midpoints lie inside it), relative to origin.
  pure subroutine segment_box(x, corners, origin, t1, t2, box)
    real(rk), intent(in) :: x(:, :), origin(3), t1(3), t2(3)
    integer(ik), intent(in) :: corners(4)
    real(rk), intent(out) :: box(4)
    real(rk) :: u, w
    integer :: c
    box = [huge(1.0_rk), -huge(1.0_rk), huge(1.0_rk), -huge(1.0_rk)]
    do c = 1, 4
      u = dot_product(x(:, corners(c)) - origin, t1)
      w = dot_product(x(:, corners(c)) - origin, t2)
      box = [min(box(1), u), max(box(2), u), min(box(3), w), max(box(4), w)]
    end do
  end subroutine segment_box

  !> A segment's facets projected on the plane spanned by t1, t2 (relative to
  !> origin) and their bounding boxes.
  pure subroutine project_facets(facets, origin, t1, t2, f2, box)
    real(rk), intent(in) :: facets(3, 3, SEGMENT_FACET_COUNT), origin(3), t1(3), t2(3)
    real(rk), intent(out) :: f2(2, 3, SEGMENT_FACET_COUNT), box(4, SEGMENT_FACET_COUNT)
    integer :: i, v
    do i = 1, SEGMENT_FACET_COUNT
      do v = 1, 3
        f2(1, v, i) = dot_product(facets(:, v, i) - origin, t1)
        f2(2, v, i) = dot_product(facets(:, v, i) - origin, t2)
      end do
      box(:, i) = [minval(f2(1, :, i)), maxval(f2(1, :, i)), minval(f2(2, :, i)), &
          maxval(f2(2, :, i))]
    end do
  end subroutine project_facets

  !> Bounding box (min t1, max t1, min t2, max t2) of a facet projected on the
  !> plane spanned by t1, t2.
  pure subroutine facet_box(facet, t1, t2, box)
    real(rk), intent(in) :: facet(3, 3), t1(3), t2(3)
    real(rk), intent(out) :: box(4)
    real(rk) :: u(3), w(3)
    integer :: k
    do k = 1, 3
      u(k) = dot_product(facet(:, k), t1)
      w(k) = dot_product(facet(:, k), t2)
    end do
    box = [minval(u), maxval(u), minval(w), maxval(w)]
  end subroutine facet_box

  !> Two projected boxes overlap (with a relative margin for round-off; the
  !> exact clip decides).
  pure logical function boxes_meet(a, b)
    real(rk), intent(in) :: a(4), b(4)
    real(rk) :: pad
    pad = 1.0e-9_rk * max(a(2) - a(1), a(4) - a(3), b(2) - b(1), b(4) - b(3))
    boxes_meet = a(1) <= b(2) + pad .and. b(1) <= a(2) + pad .and. a(3) <= b(4) + pad .and. &
        b(3) <= a(4) + pad
  end function boxes_meet

  !> The part of a facet's own area that an overlap s0, measured in the plane
  !> normal to nrm, covers: s0 times the facet's area over its projected area.
  !> Divided by the nodal area it is the node's share carried by the overlap;
  !> the shares of a node fully covered sum to one to round-off even when its
  !> facets are not normal to nrm (a warped or tilted surface), so that a
  !> matching interface acts exactly on whole nodes.
  pure real(rk) function covered(facet_normal, s0, nrm) result(area)
    real(rk), intent(in) :: facet_normal(3), s0, nrm(3)
    real(rk) :: projected
    projected = abs(dot_product(facet_normal, nrm))
    area = s0
    if (projected > 0.0_rk) area = s0 / projected
  end function covered

  !> Distance along nrm from point c to the plane through q with normal n
  !> (c + t nrm lies on the plane).
  pure real(rk) function plane_offset(q, n, c, nrm) result(t)
    real(rk), intent(in) :: q(3), n(3), c(3), nrm(3)
    real(rk) :: denominator
    denominator = dot_product(nrm, n)
    t = 0.0_rk
    if (abs(denominator) > 1.0e-3_rk) t = dot_product(q - c, n) / denominator
  end function plane_offset

  !> Bilinear shape functions of a segment at natural coordinates (xi, eta).
  pure subroutine bilinear_shape(xi, eta, shape)
    real(rk), intent(in) :: xi, eta
    real(rk), intent(out) :: shape(4)
    shape(1) = 0.25_rk * (1.0_rk - xi) * (1.0_rk - eta)
    shape(2) = 0.25_rk * (1.0_rk + xi) * (1.0_rk - eta)
    shape(3) = 0.25_rk * (1.0_rk + xi) * (1.0_rk + eta)
    shape(4) = 0.25_rk * (1.0_rk - xi) * (1.0_rk + eta)
  end subroutine bilinear_shape

end module contact_geometry
