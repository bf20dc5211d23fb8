!> Meshes from other tools: one entry point for the importers (Gmsh .msh,
!> Exodus II) and a summary of an imported part (zones and volume per block,
!> faces and area per face set) that the set-up prints, so that a user can
!> check what was read against the meshing tool.
module mesh_import
  use core_kinds, only: rk
  use core_status, only: status_t
  use mesh_geometry, only: hex_volume, quad_vector_area, HEX_FACE_NODES
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_gmsh, only: mesh_read_gmsh
  use mesh_exodus, only: mesh_read_exodus
  implicit none
  private
  public :: mesh_import_file, mesh_import_group_kind, mesh_import_summary, mesh_set_area

contains

  !> Read the mesh file path of the given type ('gmsh' or 'exodus'); groups
  !> are the names of the file's volume groups (zone_block indexes them).
  subroutine mesh_import_file(mesh_type, path, mesh, groups, status)
    character(len=*), intent(in) :: mesh_type !< 'gmsh' or 'exodus'
    character(len=*), intent(in) :: path !< full path of the file
    type(global_mesh_t), intent(inout) :: mesh
    character(len=NAME_LEN), allocatable, intent(out) :: groups(:)
    type(status_t), intent(inout) :: status
    select case (mesh_type)
    case ('gmsh')
      call mesh_read_gmsh(path, mesh, groups, status)
    case ('exodus')
      call mesh_read_exodus(path, mesh, groups, status)
    case default
      allocate(groups(0))
      call status%add('mesh file '''//trim(path)//''': unknown mesh file type '''// &
          trim(mesh_type)//'''')
    end select
  end subroutine mesh_import_file

  !> What the file calls the groups that become blocks, for messages.
  function mesh_import_group_kind(mesh_type) result(kind)
    character(len=*), intent(in) :: mesh_type
    character(len=:), allocatable :: kind
    if (mesh_type == 'exodus') then
      kind = 'element block'
    else
      kind = 'physical volume'
    end if
  end function mesh_import_group_kind

  !> Area of face set k of mesh: the sum of the faces' vector-area norms
  !> (exact for planar faces); centre: the area-weighted mean of the faces'
  !> vertex averages (0 for an empty set).
  subroutine mesh_set_area(mesh, k, area, centre)
    type(global_mesh_t), intent(in) :: mesh
    integer, intent(in) :: k
    real(rk), intent(out) :: area, centre(3)
    integer :: i
    real(rk) :: p(3, 4), a
    area = 0.0_rk
    centre = 0.0_rk
    do i = mesh%set_start(k), mesh%set_start(k + 1) - 1
      p = mesh%coordinates(:, mesh%connectivity(HEX_FACE_NODES(:, mesh%set_face(i)), &
          mesh%set_zone(i)))
      a = norm2(quad_vector_area(p))
      area = area + a
      centre = centre + a * 0.25_rk * sum(p, dim=2)
    end do
    if (area > 0.0_rk) centre = centre / area
  end subroutine mesh_set_area

  !> Lines describing an imported part (before any rotation or offset):
  !> nodes, zones and volume; per group its zones and volume; per face set its
  !> faces, area and centre. Numbers in full precision (es24.16).
  subroutine mesh_import_summary(mesh, groups, title, lines)
    type(global_mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: groups(:) !< zone_block indexes them
    character(len=*), intent(in) :: title !< first line
    character(len=200), allocatable, intent(out) :: lines(:)
    real(rk), allocatable :: volume(:)
    integer, allocatable :: zones(:)
    integer :: z, g, k, n
    real(rk) :: v, area, centre(3)

    allocate(volume(size(groups)), zones(size(groups)))
    volume = 0.0_rk
    zones = 0
    do z = 1, mesh%nzone
      v = hex_volume(mesh%coordinates(:, mesh%connectivity(:, z)))
      g = mesh%zone_block(z)
      if (g >= 1 .and. g <= size(groups)) then
        volume(g) = volume(g) + v
        zones(g) = zones(g) + 1
      end if
    end do
    allocate(lines(2 + size(groups) + mesh%nset))
    lines(1) = title
    write(lines(2), '(a,i0,a,i0,a,es24.16)') '  ', mesh%nnode, ' nodes, ', mesh%nzone, &
        ' zones, volume ', sum(volume)
    n = 2
    do g = 1, size(groups)
      n = n + 1
      write(lines(n), '(3a,i0,a,es24.16)') '  block ''', trim(groups(g)), ''': ', zones(g), &
          ' zones, volume ', volume(g)
    end do
    do k = 1, mesh%nset
      n = n + 1
      call mesh_set_area(mesh, k, area, centre)
      write(lines(n), '(3a,i0,a,es24.16,a,3es24.16)') '  face set ''', trim(mesh%set_name(k)), &
          ''': ', mesh%set_start(k + 1) - mesh%set_start(k), ' faces, area ', area, &
          ', centre', centre
    end do
  end subroutine mesh_import_summary

end module mesh_import
