!> Geometry kernels of the trilinear hexahedron (plain arrays, no MPI, no I/O).
!>
!> Node order: 1..4 the face zeta = -1 counter-clockwise seen from outside
!> the opposite face, 5..8 above them (the usual VTK/Exodus hex order).
!> With x(xi,eta,zeta) = c + xi a1 + eta a2 + zeta a3 + eta zeta b1
!> + xi zeta b2 + xi eta b3 + xi eta zeta d, the exact volume of the trilinear
!> hex is  V = 8 a1.(a2 x a3) + 8/3 [a1.(b3 x b2) + a2.(b1 x b3) + a3.(b2 x b1)]
!> (d drops out on integration), and its derivative with respect to the node
!> coordinates (the B-matrix) follows by the chain rule; see docs/theory.md.
module mesh_geometry
  use core_kinds, only: rk
  implicit none
  private
  public :: hex_volume, hex_volume_gradient, hex_face_area, quad_vector_area
  public :: quad_node_area_vectors, hex_characteristic_length, hex_centroid
  public :: hex_geometry_lanes, HEX_LANES
  public :: HEX_FACE_NODES, SIGN_XI, SIGN_ETA, SIGN_ZETA, HOURGLASS_BASE
  public :: cross

  !> Local nodes of the six faces, ordered so the normal points outward.
  integer, parameter :: HEX_FACE_NODES(4, 6) = reshape([ &
      1, 4, 3, 2, &
      5, 6, 7, 8, &
      1, 2, 6, 5, &
      2, 3, 7, 6, &
      3, 4, 8, 7, &
      4, 1, 5, 8], [4, 6])
  real(rk), parameter :: SIGN_XI(8) = [-1, 1, 1, -1, -1, 1, 1, -1] * 1.0_rk
  real(rk), parameter :: SIGN_ETA(8) = [-1, -1, 1, 1, -1, -1, 1, 1] * 1.0_rk
  real(rk), parameter :: SIGN_ZETA(8) = [-1, -1, -1, -1, 1, 1, 1, 1] * 1.0_rk
  !> The four hourglass base vectors (xi eta, eta zeta, xi zeta, xi eta zeta).
  real(rk), parameter :: HOURGLASS_BASE(8, 4) = reshape([ &
      SIGN_XI * SIGN_ETA, SIGN_ETA * SIGN_ZETA, SIGN_XI * SIGN_ZETA, &
      SIGN_XI * SIGN_ETA * SIGN_ZETA], [8, 4])
  real(rk), parameter :: EIGHTH = 0.125_rk, EIGHT_THIRDS = 8.0_rk / 3.0_rk
  !> Hexes per call of hex_geometry_lanes.
  integer, parameter :: HEX_LANES = 4

contains

  !> Cross product of two 3-vectors.
  pure function cross(a, b) result(c)
    real(rk), intent(in) :: a(3), b(3)
    real(rk) :: c(3)
    c(1) = a(2) * b(3) - a(3) * b(2)
    c(2) = a(3) * b(1) - a(1) * b(3)
    c(3) = a(1) * b(2) - a(2) * b(1)
  end function cross

  !> The six shape vectors a1, a2, a3, b1, b2, b3 of the trilinear map.
  pure subroutine shape_vectors(x, a1, a2, a3, b1, b2, b3)
    real(rk), intent(in) :: x(3, 8)
    real(rk), intent(out) :: a1(3), a2(3), a3(3), b1(3), b2(3), b3(3)
    ! Signs of SIGN_XI, SIGN_ETA, SIGN_ZETA and their products written out: the
    ! same additions in the same order as a loop over k from zero (bitwise equal).
    a1 = -x(:, 1) + x(:, 2) + x(:, 3) - x(:, 4) - x(:, 5) + x(:, 6) + x(:, 7) - x(:, 8)
    a2 = -x(:, 1) - x(:, 2) + x(:, 3) + x(:, 4) - x(:, 5) - x(:, 6) + x(:, 7) + x(:, 8)
    a3 = -x(:, 1) - x(:, 2) - x(:, 3) - x(:, 4) + x(:, 5) + x(:, 6) + x(:, 7) + x(:, 8)
    b1 = x(:, 1) + x(:, 2) - x(:, 3) - x(:, 4) - x(:, 5) - x(:, 6) + x(:, 7) + x(:, 8)
    b2 = x(:, 1) - x(:, 2) - x(:, 3) + x(:, 4) - x(:, 5) + x(:, 6) + x(:, 7) - x(:, 8)
    b3 = x(:, 1) - x(:, 2) + x(:, 3) - x(:, 4) + x(:, 5) - x(:, 6) + x(:, 7) - x(:, 8)
    a1 = EIGHTH * a1
    a2 = EIGHTH * a2
    a3 = EIGHTH * a3
    b1 = EIGHTH * b1
    b2 = EIGHTH * b2
    b3 = EIGHTH * b3
  end subroutine shape_vectors

  !> Exact volume of the trilinear hexahedron with corners x(:, 1:8).
  pure function hex_volume(x) result(volume)
    real(rk), intent(in) :: x(3, 8) !< node coordinates
    real(rk) :: volume
    real(rk) :: a1(3), a2(3), a3(3), b1(3), b2(3), b3(3)
    call shape_vectors(x, a1, a2, a3, b1, b2, b3)
    volume = 8.0_rk * dot_product(a1, cross(a2, a3)) + EIGHT_THIRDS * ( &
        dot_product(a1, cross(b3, b2)) + dot_product(a2, cross(b1, b3)) &
        + dot_product(a3, cross(b2, b1)))
  end function hex_volume

  !> Volume and its exact gradient b(:, k) = dV/dx_k (the B-matrix) of one hex:
  !> hex_geometry_lanes with the hex in every lane, so there is one B-matrix
  !> formula and the unit tests exercise the one the cycle runs.
  pure subroutine hex_volume_gradient(x, volume, b)
    real(rk), intent(in) :: x(3, 8) !< node coordinates
    real(rk), intent(out) :: volume !< exact trilinear volume
    real(rk), intent(out) :: b(3, 8) !< dV/dx of each node
    real(rk) :: xl(HEX_LANES, 3, 8), bl(HEX_LANES, 3, 8), vol(HEX_LANES), len(HEX_LANES)
    real(rk) :: axes(HEX_LANES, 3, 3)
    integer :: i
    do i = 1, HEX_LANES
      xl(i, :, :) = x
    end do
    call hex_geometry_lanes(xl, vol, bl, len, axes)
    volume = vol(1)
    b = bl(1, :, :)
  end subroutine hex_volume_gradient

  !> Volume, B-matrix and characteristic length of HEX_LANES hexes at once (the
  !> zone kinematics), the hex index first in every array so that each
  !> statement is a vector operation over the hexes: bitwise the values of
  !> hex_volume_gradient and hex_characteristic_length hex by hex (the same
  !> operations in the same order; the dot products from zero as
  !> dot_product's), whatever the sign of the volume. Also the sums along the
  !> logical directions, axes(:, :, d) = sum_k s_k x_k with the signs of
  !> SIGN_XI, SIGN_ETA, SIGN_ZETA (8 a_d exactly: a scaling by a power of two).
  pure subroutine hex_geometry_lanes(x, volume, b, length, axes)
    real(rk), intent(in) :: x(HEX_LANES, 3, 8) !< node coordinates
    real(rk), intent(out) :: volume(HEX_LANES), b(HEX_LANES, 3, 8), length(HEX_LANES)
    real(rk), intent(out) :: axes(HEX_LANES, 3, 3)
    real(rk), dimension(HEX_LANES, 3) :: a1, a2, a3, b1, b2, b3, ga1, ga2, ga3, gb1, gb2, gb3
    real(rk), dimension(HEX_LANES, 3) :: d1, d2, c
    real(rk) :: a2max(HEX_LANES), s(HEX_LANES)
    integer :: d, f
    do d = 1, 3
      a1(:, d) = -x(:, d, 1) + x(:, d, 2) + x(:, d, 3) - x(:, d, 4) - x(:, d, 5) + x(:, d, 6) &
          + x(:, d, 7) - x(:, d, 8)
      a2(:, d) = -x(:, d, 1) - x(:, d, 2) + x(:, d, 3) + x(:, d, 4) - x(:, d, 5) - x(:, d, 6) &
          + x(:, d, 7) + x(:, d, 8)
      a3(:, d) = -x(:, d, 1) - x(:, d, 2) - x(:, d, 3) - x(:, d, 4) + x(:, d, 5) + x(:, d, 6) &
          + x(:, d, 7) + x(:, d, 8)
      b1(:, d) = x(:, d, 1) + x(:, d, 2) - x(:, d, 3) - x(:, d, 4) - x(:, d, 5) - x(:, d, 6) &
          + x(:, d, 7) + x(:, d, 8)
      b2(:, d) = x(:, d, 1) - x(:, d, 2) - x(:, d, 3) + x(:, d, 4) - x(:, d, 5) + x(:, d, 6) &
          + x(:, d, 7) - x(:, d, 8)
      b3(:, d) = x(:, d, 1) - x(:, d, 2) + x(:, d, 3) - x(:, d, 4) + x(:, d, 5) - x(:, d, 6) &
          + x(:, d, 7) - x(:, d, 8)
    end do
    a1 = EIGHTH * a1
    a2 = EIGHTH * a2
    a3 = EIGHTH * a3
    b1 = EIGHTH * b1
    b2 = EIGHTH * b2
    b3 = EIGHTH * b3
    axes(:, :, 1) = 8.0_rk * a1
    axes(:, :, 2) = 8.0_rk * a2
    axes(:, :, 3) = 8.0_rk * a3
    ga1 = 8.0_rk * cross_lanes(a2, a3) + EIGHT_THIRDS * cross_lanes(b3, b2)
    ga2 = 8.0_rk * cross_lanes(a3, a1) + EIGHT_THIRDS * cross_lanes(b1, b3)
    ga3 = 8.0_rk * cross_lanes(a1, a2) + EIGHT_THIRDS * cross_lanes(b2, b1)
    gb1 = EIGHT_THIRDS * (cross_lanes(b3, a2) + cross_lanes(a3, b2))
    gb2 = EIGHT_THIRDS * (cross_lanes(b1, a3) + cross_lanes(a1, b3))
    gb3 = EIGHT_THIRDS * (cross_lanes(a2, b1) + cross_lanes(b2, a1))
    volume = 8.0_rk * dot_lanes(a1, cross_lanes(a2, a3)) + EIGHT_THIRDS * ( &
        dot_lanes(a1, cross_lanes(b3, b2)) + dot_lanes(a2, cross_lanes(b1, b3)) &
        + dot_lanes(a3, cross_lanes(b2, b1)))
    b(:, :, 1) = EIGHTH * (-ga1 - ga2 - ga3 + gb1 + gb2 + gb3)
    b(:, :, 2) = EIGHTH * (ga1 - ga2 - ga3 + gb1 - gb2 - gb3)
    b(:, :, 3) = EIGHTH * (ga1 + ga2 - ga3 - gb1 - gb2 + gb3)
    b(:, :, 4) = EIGHTH * (-ga1 + ga2 - ga3 - gb1 + gb2 - gb3)
    b(:, :, 5) = EIGHTH * (-ga1 - ga2 + ga3 - gb1 - gb2 + gb3)
    b(:, :, 6) = EIGHTH * (ga1 - ga2 + ga3 - gb1 + gb2 - gb3)
    b(:, :, 7) = EIGHTH * (ga1 + ga2 + ga3 + gb1 + gb2 + gb3)
    b(:, :, 8) = EIGHTH * (-ga1 + ga2 + ga3 + gb1 - gb2 - gb3)
    ! hex_characteristic_length.
    a2max = 0.0_rk
    do f = 1, 6
      d1 = x(:, :, HEX_FACE_NODES(3, f)) - x(:, :, HEX_FACE_NODES(1, f))
      d2 = x(:, :, HEX_FACE_NODES(4, f)) - x(:, :, HEX_FACE_NODES(2, f))
      c = cross_lanes(d1, d2)
      s = c(:, 1)**2 + c(:, 2)**2 + c(:, 3)**2
      a2max = max(a2max, s)
    end do
    s = merge(a2max, 1.0_rk, a2max > 0.0_rk)
    length = merge(2.0_rk * volume / sqrt(s), 0.0_rk, a2max > 0.0_rk)
  end subroutine hex_geometry_lanes

  !> cross of HEX_LANES pairs of 3-vectors (hex index first).
  pure function cross_lanes(a, b) result(c)
    real(rk), intent(in) :: a(HEX_LANES, 3), b(HEX_LANES, 3)
    real(rk) :: c(HEX_LANES, 3)
    c(:, 1) = a(:, 2) * b(:, 3) - a(:, 3) * b(:, 2)
    c(:, 2) = a(:, 3) * b(:, 1) - a(:, 1) * b(:, 3)
    c(:, 3) = a(:, 1) * b(:, 2) - a(:, 2) * b(:, 1)
  end function cross_lanes

  !> dot_product of HEX_LANES pairs of 3-vectors, summed from zero as it is.
  pure function dot_lanes(a, b) result(c)
    real(rk), intent(in) :: a(HEX_LANES, 3), b(HEX_LANES, 3)
    real(rk) :: c(HEX_LANES)
    c = 0.0_rk
    c = c + a(:, 1) * b(:, 1)
    c = c + a(:, 2) * b(:, 2)
    c = c + a(:, 3) * b(:, 3)
  end function dot_lanes

  !> Vector area of a bilinear quadrilateral p1..p4: the exact integral of n dA.
  pure function quad_vector_area(p) result(area)
    real(rk), intent(in) :: p(3, 4)
    real(rk) :: area(3)
    area = 0.5_rk * cross(p(:, 3) - p(:, 1), p(:, 4) - p(:, 2))
  end function quad_vector_area

  !> Exact nodal integrals of N_k n dA over a bilinear quadrilateral: the force
  !> on node k of a unit pressure acting on the face is -a(:, k).
  pure subroutine quad_node_area_vectors(p, a)
    real(rk), intent(in) :: p(3, 4) !< corners, counter-clockwise about the normal
    real(rk), intent(out) :: a(3, 4)
    real(rk) :: e1(3), e2(3), d(3), c0(3), cs(3), ct(3)
    ! x(s,t) = p1 + s e1 + t e2 + s t d on [0,1]^2; x_s x x_t = c0 + s cs + t ct.
    e1 = p(:, 2) - p(:, 1)
    e2 = p(:, 4) - p(:, 1)
    d = p(:, 1) - p(:, 2) + p(:, 3) - p(:, 4)
    c0 = cross(e1, e2)
    cs = cross(e1, d)
    ct = cross(d, e2)
    ! Integrals of the shape functions against 1, s and t.
    a(:, 1) = c0 / 4.0_rk + cs / 12.0_rk + ct / 12.0_rk
    a(:, 2) = c0 / 4.0_rk + cs / 6.0_rk + ct / 12.0_rk
    a(:, 3) = c0 / 4.0_rk + cs / 6.0_rk + ct / 6.0_rk
    a(:, 4) = c0 / 4.0_rk + cs / 12.0_rk + ct / 6.0_rk
  end subroutine quad_node_area_vectors

  !> Magnitude of the vector area of face f (1..6) of the hex.
  pure function hex_face_area(x, f) result(area)
    real(rk), intent(in) :: x(3, 8)
    integer, intent(in) :: f
    real(rk) :: area
    real(rk) :: d1(3), d2(3)
    d1 = x(:, HEX_FACE_NODES(3, f)) - x(:, HEX_FACE_NODES(1, f))
    d2 = x(:, HEX_FACE_NODES(4, f)) - x(:, HEX_FACE_NODES(2, f))
    area = 0.5_rk * norm2(cross(d1, d2))
  end function hex_face_area

  !> Characteristic length: volume over the largest face area.
  pure function hex_characteristic_length(x, volume) result(length)
    real(rk), intent(in) :: x(3, 8)
    real(rk), intent(in) :: volume !< the hex volume (already known)
    real(rk) :: length
    real(rk) :: a2max, c(3)
    integer :: f
    ! Compare squared doubled areas; one square root at the end.
    a2max = 0.0_rk
    do f = 1, 6
      c = cross(x(:, HEX_FACE_NODES(3, f)) - x(:, HEX_FACE_NODES(1, f)), &
          x(:, HEX_FACE_NODES(4, f)) - x(:, HEX_FACE_NODES(2, f)))
      a2max = max(a2max, c(1)**2 + c(2)**2 + c(3)**2)
    end do
    if (a2max > 0.0_rk) then
      length = 2.0_rk * volume / sqrt(a2max)
    else
      length = 0.0_rk
    end if
  end function hex_characteristic_length

  !> Mean of the eight corners.
  pure function hex_centroid(x) result(c)
    real(rk), intent(in) :: x(3, 8)
    real(rk) :: c(3)
    c = sum(x, dim=2) * EIGHTH
  end function hex_centroid

end module mesh_geometry
